// Device-layer throughput, each against a reference measured in the same run:
//
//   SimCameraGrab       frames/s the simulated camera serves (test pattern,
//                       640×480 GREY, virtual clock) vs PatternCopy, a plain
//                       copy of one such frame: the camera's bookkeeping
//                       (sequence, timestamps, buffers) on top of the pixels.
//   UsbEncodeDecode     protocol frames encoded + decoded per second (STATUS
//                       reply, 11 bytes) vs Crc8Only, the CRC of the same bytes.
//   UsbExchange         full host↔simulated-board exchanges (UsbController::
//                       status(): encode, endpoints, board decode/execute/encode,
//                       host decode and checks) vs UsbEncodeDecode.
//   RampTimes           trapezoid step times per second (3200-step move) vs
//                       SqrtLoop, one std::sqrt per step (the closed form's core).
//   StepperPulseTrain   steps/s the stepper driver issues on a simulated chip
//                       (two recorded transitions per step, virtual clock)
//                       vs RampTimes.
//
//   build/bench/drivers_bench [--benchmark_filter=Usb]
//
// Issue 6 sets no performance targets; these numbers show where the time of
// the simulated station goes.
#include "bench/benchmark_main.h"
#include "drivers/stepper_turntable.h"
#include "drivers/trapezoid_ramp.h"
#include "drivers/usb_controller.h"
#include "drivers/usb_protocol.h"
#include "sim/devices/sim_camera.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/sim_usb_board.h"
#include "sim/devices/virtual_clock.h"

#include <benchmark/benchmark.h>
#include <cmath>

namespace {

using namespace scanstation;
using namespace std::chrono_literals;

void SimCameraGrab(benchmark::State& state) {
  sim::VirtualClock clock;
  sim::SimCamera camera(std::make_unique<sim::TestPattern>(), clock);
  camera.set_format({drivers::PixelFormat::grey, {640, 480}, 4});
  camera.start();
  for (auto _ : state) benchmark::DoNotOptimize(camera.grab(1000ms));
  state.counters["frames/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(SimCameraGrab);

void PatternCopy(benchmark::State& state) {
  sim::VirtualClock clock;
  sim::SimCamera camera(std::make_unique<sim::TestPattern>(), clock);
  camera.set_format({drivers::PixelFormat::grey, {640, 480}, 4});
  camera.start();
  const cv::Mat frame = camera.grab(1000ms).image;
  for (auto _ : state) benchmark::DoNotOptimize(frame.clone());
  state.counters["frames/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(PatternCopy);

drivers::usb::Message status_reply() {
  return {drivers::usb::kReplyMagic, drivers::usb::Command::status, 7,
          drivers::usb::PayloadWriter().u8(0).u8(drivers::usb::kFlagEnabled).u8(1).i32(-400).bytes()};
}

void UsbEncodeDecode(benchmark::State& state) {
  const auto message = status_reply();
  for (auto _ : state) {
    const auto bytes = drivers::usb::encode(message);
    benchmark::DoNotOptimize(drivers::usb::decode(bytes, drivers::usb::kReplyMagic));
  }
  state.counters["frames/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(UsbEncodeDecode);

void Crc8Only(benchmark::State& state) {
  const auto bytes = drivers::usb::encode(status_reply());
  for (auto _ : state) benchmark::DoNotOptimize(drivers::usb::crc8(bytes));
  state.counters["frames/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(Crc8Only);

void UsbExchange(benchmark::State& state) {
  sim::VirtualClock clock;
  sim::SimUsbBoard board(clock);
  drivers::UsbController controller(board.endpoints(), 100ms);
  for (auto _ : state) benchmark::DoNotOptimize(controller.status());
  state.counters["exchanges/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(UsbExchange);

void RampTimes(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(drivers::trapezoid_step_times(3200, 533.3, 1066.7));
  state.counters["steps/s"] = benchmark::Counter(3200.0 * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(RampTimes);

void SqrtLoop(benchmark::State& state) {
  std::vector<double> out(3200);
  for (auto _ : state) {
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = std::sqrt(2.0 * double(k + 1) / 1066.7);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["steps/s"] = benchmark::Counter(3200.0 * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(SqrtLoop);

void StepperPulseTrain(benchmark::State& state) {
  sim::VirtualClock clock;
  for (auto _ : state) {
    state.PauseTiming();
    // A fresh chip per move keeps the recorded history (and memory) bounded.
    auto chip = std::make_unique<sim::SimGpioChip>("simchip0", std::vector<std::string>{"STEP", "DIR", "EN"}, clock);
    drivers::StepperTurntable table(
        drivers::StepperLines{chip->request_output({"", 0u, ""}, "bench", false),
                              chip->request_output({"", 1u, ""}, "bench", false),
                              chip->request_output({"", 2u, ""}, "bench", false), nullptr},
        clock, {});
    state.ResumeTiming();
    table.rotate_by(360.0);  // 3200 steps
  }
  state.counters["steps/s"] = benchmark::Counter(3200.0 * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(StepperPulseTrain);

}  // namespace

int main(int argc, char** argv) { return scanstation::bench::benchmark_main(argc, argv); }
