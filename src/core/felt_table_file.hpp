#pragma once
// The felt-signal table of the last `mallet calibrate actuator --verify`, kept in the state
// folder (actuator_felt.csv) so that `mallet bench report` can show it beside the speed
// tables. One row per strike:
//   material,speed_m_per_s,table_decay_per_s,table_freq_hz,decay_before,freq_before,
//   decay_after,freq_after,calibration,verified_utc
// B (1/s) and f (Hz) fitted from the sensor without and with the inverse; an empty field
// where there was no fit, or no calibration (`calibration`: its hash, empty when none).
#include <filesystem>
#include <string>
#include <vector>

namespace mallet {

struct FeltRecord {
  std::string material;
  double speed_m_per_s = 0;
  double table_decay_per_s = 0, table_freq_hz = 0;
  double decay_before = 0, freq_before = 0;  //!< NaN: no fit
  double decay_after = 0, freq_after = 0;    //!< NaN: no fit, or no calibration
  std::string calibration;                   //!< the calibration's hash; empty: none
  std::string verified_utc;
};

inline constexpr const char* kFeltHeader =
    "material,speed_m_per_s,table_decay_per_s,table_freq_hz,decay_before,freq_before,decay_after,freq_after,"
    "calibration,verified_utc";

std::string format_felt_table(const std::vector<FeltRecord>& rows);
//! Every problem a FileError: FILE:LINE: problem (csv_file.hpp's wording).
std::vector<FeltRecord> read_felt_table(const std::filesystem::path& path);

}  // namespace mallet
