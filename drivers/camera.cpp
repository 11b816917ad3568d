#include "drivers/camera.h"

#include "core/errors.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace scanstation::drivers {

namespace {

struct FormatName {
  PixelFormat format;
  const char* name;
};
constexpr FormatName kFormatNames[] = {
    {PixelFormat::grey, "GREY"}, {PixelFormat::y16, "Y16"}, {PixelFormat::yuyv, "YUYV"}, {PixelFormat::mjpeg, "MJPG"}};

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// Distance between frame sizes: log of the pixel-count ratio plus log of the
// aspect ratio, so 1280×720 is nearer to 1280×800 than to 640×360.
double size_distance(FrameSize a, FrameSize b) {
  const double area = std::log(double(a.width) * a.height / (double(b.width) * b.height));
  const double aspect = std::log(double(a.width) * b.height / (double(a.height) * b.width));
  return std::abs(area) + std::abs(aspect);
}

}  // namespace

std::string pixel_format_name(PixelFormat format) {
  for (const auto& [f, name] : kFormatNames)
    if (f == format) return name;
  return "?";
}

std::optional<PixelFormat> parse_pixel_format(const std::string& name) {
  const std::string wanted = upper(name) == "MJPEG" ? "MJPG" : upper(name);
  for (const auto& [f, known] : kFormatNames)
    if (wanted == known) return f;
  return std::nullopt;
}

std::string control_key(const std::string& label) {
  std::string key;
  for (const char c : label) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!key.empty() && key.back() != '_') {
      key += '_';
    }
  }
  while (!key.empty() && key.back() == '_') key.pop_back();
  return key;
}

FormatAdjustment nearest_format(const std::vector<FormatDescription>& offered, const CameraFormat& wanted) {
  const auto same = std::find_if(offered.begin(), offered.end(), [&](const auto& d) { return d.format == wanted.format; });
  const auto chosen = same != offered.end() ? same : std::find_if(offered.begin(), offered.end(),
                                                                  [](const auto& d) { return !d.sizes.empty(); });
  if (chosen == offered.end() || chosen->sizes.empty()) throw InvalidInput("the camera offers no usable pixel format");
  FormatAdjustment result;
  result.applied.format = chosen->format;
  double best = std::numeric_limits<double>::infinity();
  for (const FrameSize size : chosen->sizes) {
    const double d = size_distance(size, wanted.size);
    if (d < best) best = d, result.applied.size = size;
  }
  result.applied.buffer_count = std::clamp(wanted.buffer_count, 2, 32);
  std::string note;
  if (result.applied.format != wanted.format)
    note += "pixel format " + pixel_format_name(wanted.format) + " not offered, using " +
            pixel_format_name(result.applied.format) + "; ";
  if (!(result.applied.size == wanted.size))
    note += "frame size " + std::to_string(wanted.size.width) + "x" + std::to_string(wanted.size.height) +
            " not offered, using " + std::to_string(result.applied.size.width) + "x" +
            std::to_string(result.applied.size.height) + "; ";
  if (result.applied.buffer_count != wanted.buffer_count)
    note += "buffer count " + std::to_string(wanted.buffer_count) + " clamped to " +
            std::to_string(result.applied.buffer_count) + "; ";
  result.adjusted = !note.empty();
  if (result.adjusted) result.note = note.substr(0, note.size() - 2);
  return result;
}

std::int64_t clamp_control(const ControlInfo& control, std::int64_t value) {
  const std::int64_t step = std::max<std::int64_t>(control.step, 1);
  const std::int64_t clamped = std::clamp(value, control.minimum, control.maximum);
  const std::int64_t snapped = control.minimum + (clamped - control.minimum + step / 2) / step * step;
  return snapped > control.maximum ? snapped - step : snapped;
}

std::uint32_t SequenceCounter::dropped_before(std::uint32_t sequence) {
  // Unsigned arithmetic wraps exactly like the driver's 32-bit counter.
  const std::uint32_t dropped = last_ ? sequence - *last_ - 1u : 0u;
  last_ = sequence;
  total_ += dropped;
  return dropped;
}

}  // namespace scanstation::drivers
