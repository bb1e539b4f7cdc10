#include "ximu/ximu_registers.hpp"

#include <cmath>

#include <fmt/format.h>

#include "text/column_lookup.hpp"
#include "text/number_parsing.hpp"

namespace rockfit::io {

std::optional<double> XimuRateFromRegisterValue(long long value) {
  if (value == 0) return 0.0;
  if (value < 1 || value > 10) return std::nullopt;
  return std::ldexp(1.0, static_cast<int>(value - 1));
}

XimuRegisterSettings ReadXimuRegisters(const CsvTable& registers) {
  const auto columns = ResolveColumns(registers, {{{"Address"}, "the register address"}, {{"Value"}, "the register value"}});
  const std::size_t address_column = *columns[0];
  const std::size_t value_column = *columns[1];
  XimuRegisterSettings rates;
  bool full_scale_conflict = false;
  for (std::size_t row = 0; row < registers.row_count(); ++row) {
    const std::int64_t address = registers.Integer(row, address_column);
    if (address == kXimuGyroscopeFullScaleRegister && !full_scale_conflict) {
      const std::optional<std::int64_t> value = ParseInteger(registers.Cell(row, value_column));
      const std::optional<double> full_scale =
          value && *value >= 0 && *value <= 3 ? std::optional<double>(250.0 * std::ldexp(1.0, static_cast<int>(*value)))
                                               : std::nullopt;
      if (rates.gyroscope_full_scale_dps && full_scale != rates.gyroscope_full_scale_dps) full_scale_conflict = true;
      rates.gyroscope_full_scale_dps = full_scale_conflict ? std::nullopt : full_scale;
      continue;
    }
    if (address != kXimuInertialRateRegister && address != kXimuQuaternionRateRegister) continue;
    const std::int64_t value = registers.Integer(row, value_column);
    const std::optional<double> rate = XimuRateFromRegisterValue(value);
    const std::string name = address == kXimuInertialRateRegister ? "InertialAndMagneticDataRate (register 69)"
                                                                  : "QuaternionDataRate (register 70)";
    if (!rate) {
      registers.ThrowBadCell(row, value_column, std::to_string(value) + " for " + name,
                             "0 (disabled) or 1 … 10 (2^(v-1) Hz: 1 … 512 Hz)",
                             "The registers file is damaged; delete it and give the rate with --rate.");
    }
    std::optional<XimuRegisterRate>& slot = address == kXimuInertialRateRegister ? rates.inertial : rates.orientation;
    if (slot && slot->value != value) {
      registers.ThrowBadCell(row, value_column,
                             fmt::format("{} = {} ({:g} Hz), but {} it was {} ({:g} Hz)", name, value, *rate,
                                         FormatPosition(slot->at), slot->value, slot->rate_hz),
                             "one rate per recording",
                             "The rate was changed while recording; split the files at that packet, or record again.");
    }
    slot = XimuRegisterRate{*rate, value, registers.PositionOf(row, value_column)};
  }
  return rates;
}

}  // namespace rockfit::io
