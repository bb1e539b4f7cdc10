// The numeric rows of a comma-separated IMU file, parsed independently of the readers under test (the
// x-IMU files use '.' for decimals and ',' between cells only): tests compare what a reader returns with
// these plain numbers.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rockfit::testing {

// Every row after the header line, each cell as a double (std::stod: a cell that is not a number throws,
// so a malformed file fails the test instead of reading as zeros).
inline std::vector<std::vector<double>> ReadCsvNumbers(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace rockfit::testing
