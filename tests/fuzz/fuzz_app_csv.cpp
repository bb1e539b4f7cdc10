// libFuzzer target: phone-app and logger CSV files and the attitude integrated from their gyro (app_csv_target.hpp).
#include <cstddef>
#include <cstdint>

#include "app_csv_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::AppCsv(rockfit::fuzz::AsText(data, size));
  return 0;
}
