// zone_series.h5 of a soft-sphere run ([zone_series], Lan 1994 section 4.3): each zone's
// instantaneous mean velocity and the floor's motion at a fixed interval, for spectra and the
// floor cross-correlations of `grainflow analyze`. The observer owns its table: its keys (start,
// samples, interval), their defaults and checks are its schema's, defined in its .cpp.
#pragma once

#include <optional>

#include "grainflow/config/observer_schema.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/zone_profile.hpp"

namespace grainflow::observe {

class ZoneSeriesObserver final : public Observer {
 public:
  // [zone_series]: start (s; absent: output.average_start), samples (default 2048, at least 16),
  // interval (s; 0: 1 / (20 f), f the drive's frequency along gravity), each stored as read.
  static const ObserverSchema table;

  explicit ZoneSeriesObserver(const RunContext& run);

  std::string name() const override { return "zone_series"; }
  // Samples at the first step at or after each start + k interval.
  void sample(const Frame& now) override;
  void serialize(io::StateArchive& ar) override { ar(taken_, next_); }
  void save_streams(const std::string& folder) override {
    if (file_) file_->copy_to(folder + "/checkpoint_zone_series.h5");
  }
  void resume_streams(const std::string& folder) override {
    if (file_)
      io::resume_streams(folder + "/checkpoint_zone_series.h5",
                         {&time_, &zone_velocity_, &floor_position_, &floor_velocity_},
                         static_cast<std::size_t>(taken_));
  }
  void finish(OutputSink& out) override;

 private:
  const CaseConfig& c_;
  ZoneProfile zones_;                 // their geometry; nothing accumulated
  std::optional<io::H5Writer> file_;  // rank 0's
  io::GrowingDataset time_, zone_velocity_, floor_position_, floor_velocity_;
  double start_ = 0.0, interval_ = 0.0;
  long taken_ = 0, requested_ = 0, next_ = 0;  // next: index of the next sample time start + k interval
};

}  // namespace grainflow::observe
