#include "smoothing/patches_json.h"

#include "core/io/number_text.h"

#include <algorithm>
#include <vector>

namespace scanstation {

std::string patches_json(const BezierSurface& surface, const std::string& scheme) {
  std::string out = "{\"degree\": 3, \"scheme\": \"" + scheme + "\",\n \"control_point_order\": "
                    "[\"b300\", \"b210\", \"b201\", \"b120\", \"b111\", \"b102\", \"b030\", \"b021\", \"b012\", \"b003\"],\n"
                    " \"patches\": [";
  out.reserve(out.size() + surface.patches.size() * 600);
  // How many patches split each macro triangle (2, 3 or 6).
  std::vector<int> split(surface.macro.empty() ? 0 : *std::max_element(surface.macro.begin(), surface.macro.end()) + 1);
  for (const int f : surface.macro) ++split[f];
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    out += p == 0 ? "\n  {\"macro\": " : ",\n  {\"macro\": ";
    out += std::to_string(surface.macro[p]);
    out += ", \"split\": ";
    out += std::to_string(split[surface.macro[p]]);
    out += ", \"control_points\": [";
    for (int i = 0; i < 10; ++i) {
      out += i == 0 ? "[" : ", [";
      for (int a = 0; a < 3; ++a) {
        if (a > 0) out += ", ";
        io::append_double(out, surface.patches[p][i][a]);
      }
      out += ']';
    }
    out += "]}";
  }
  out += "\n ]\n}\n";
  return out;
}

}  // namespace scanstation
