#include "propulsion_estimator/offline/estimate_csv.h"

#include <cmath>
#include <charconv>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/logs/csv_text.h"

namespace propulsion_estimator {
namespace offline {
namespace {

const std::vector<std::string> kColumns = {"time_s",      "voltage_v",   "thrust_n",         "current_a",
                                           "power_w",     "lifted_mass_kg", "hovering",      "total_mass_kg",
                                           "mass_std_kg", "payload_kg",  "motors_out_of_domain"};

std::string rotorColumn(std::size_t k) { return "thrust_" + std::to_string(k + 1) + "_n"; }

void cell(double value, std::string* line) {
  if (!line->empty()) *line += ',';
  if (std::isnan(value)) return;
  // The shortest text that reads back as the same double (and a tenth of snprintf's cost).
  char text[32];
  const std::to_chars_result written = std::to_chars(text, text + sizeof text, value);
  line->append(text, written.ptr);
}

double number(const CsvText& table, const CsvText::Row& row, std::size_t column) {
  const std::string& field = row.fields[column];
  if (field.empty()) return kNaN;
  const std::optional<double> value = parseDecimal(field, false);
  if (!value || std::isinf(*value)) {
    throw DataError(cellWhere(table, row.line, column) + ": '" + field + "' is not a number");
  }
  return *value;
}

}  // namespace

std::string estimateCsv(const std::vector<EstimateSample>& samples) {
  const std::size_t rotors = samples.empty() ? 0 : samples.front().motor_thrust_n.size();
  std::string text;
  for (const std::string& name : kColumns) text += (text.empty() ? "" : ",") + name;
  for (std::size_t k = 0; k < rotors; ++k) text += "," + rotorColumn(k);
  text += '\n';
  for (const EstimateSample& s : samples) {
    std::string line;
    for (double value : {s.time_s, s.voltage_v, s.thrust_n, s.current_a, s.power_w, s.lifted_mass_kg,
                         s.hovering ? 1.0 : 0.0, s.total_mass_kg, s.mass_std_kg, s.payload_kg,
                         static_cast<double>(s.motors_out_of_domain)}) {
      cell(value, &line);
    }
    for (std::size_t k = 0; k < rotors; ++k) cell(k < s.motor_thrust_n.size() ? s.motor_thrust_n[k] : kNaN, &line);
    text += line + '\n';
  }
  return text;
}

std::vector<EstimateSample> parseEstimateCsv(const std::string& text, const std::string& source) {
  const CsvText table = splitCsvText(text, source);
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    if (c >= table.header.size() || table.header[c] != kColumns[c]) {
      throw DataError(source + ":" + std::to_string(table.header_line) + ": column " + std::to_string(c + 1) +
                      " should be '" + kColumns[c] + "'" +
                      (c < table.header.size() ? ", it is '" + table.header[c] + "'" : ", it is missing"));
    }
  }
  const std::size_t rotors = table.header.size() - kColumns.size();
  for (std::size_t k = 0; k < rotors; ++k) {
    if (table.header[kColumns.size() + k] != rotorColumn(k)) {
      throw DataError(source + ":" + std::to_string(table.header_line) + ": column " +
                      std::to_string(kColumns.size() + k + 1) + " should be '" + rotorColumn(k) + "', it is '" +
                      table.header[kColumns.size() + k] + "'");
    }
  }
  std::vector<EstimateSample> samples;
  samples.reserve(table.rows.size());
  for (const CsvText::Row& row : table.rows) {
    EstimateSample s;
    s.time_s = number(table, row, 0);
    s.voltage_v = number(table, row, 1);
    s.thrust_n = number(table, row, 2);
    s.current_a = number(table, row, 3);
    s.power_w = number(table, row, 4);
    s.lifted_mass_kg = number(table, row, 5);
    s.hovering = number(table, row, 6) == 1.0;
    s.total_mass_kg = number(table, row, 7);
    s.mass_std_kg = number(table, row, 8);
    s.payload_kg = number(table, row, 9);
    s.motors_out_of_domain = static_cast<int>(number(table, row, 10));
    for (std::size_t k = 0; k < rotors; ++k) s.motor_thrust_n.push_back(number(table, row, kColumns.size() + k));
    samples.push_back(std::move(s));
  }
  return samples;
}

}  // namespace offline
}  // namespace propulsion_estimator
