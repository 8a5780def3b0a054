#pragma once
// The pipeline as real processes: relplane-segmenter and relplane-mapper started on private
// buses (clouds on their own unless --one-bus), fed the benchmark's clouds at one rate, timed
// from this process; and the bus floor's ping-pong with relplane-bus-echo.

#include <cstdint>
#include <string>
#include <vector>

#include "bus_floor.hpp"
#include "latency_table.hpp"

namespace relplane::bench {

// relplane-bench's flags.
struct Flags {
  std::string scenario;
  std::string out;
  // 300: the rate the budget asks to hold, measured directly rather than between 240 and 480.
  std::vector<double> rates = {30, 60, 120, 240, 300, 480, 960, 0};
  std::vector<double> large_rates = {30, 60};
  int frames = 300;
  int large_frames = 90;
  int floor_pings = 200;
  // Frames sent to each fresh pipeline before the timed ones: its first clouds of a size pay for
  // the services' buffers and first-touch pages, which a service running for hours pays once.
  // They are timed apart (RateResult::warmup_ms), not dropped from the report.
  int warmup_frames = 2;
  bool skip_large = false;
  bool one_bus = false;
  bool verbose = false;
};

// The floor of the bus the pipeline runs on, as MeasureFloor in pipeline_run.cpp says.
BusFloor MeasureFloor(const Flags& flags, const std::string& bin_dir, size_t cloud_bytes);

// Fresh segmenter and mapper processes fed `clouds` at `rate_hz` (0: unpaced), after
// Flags::warmup_frames untimed ones; each timed frame's end to end goes to `e2e_ms`.
RateResult RunAtRate(const Flags& flags, const std::string& bin_dir,
                     const std::vector<std::vector<uint8_t>>& clouds, double rate_hz,
                     std::vector<double>* e2e_ms);

}  // namespace relplane::bench
