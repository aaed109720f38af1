#include "propulsion_estimator/logs/csv_text.h"

#include <csv.h>

#include <charconv>
#include <cmath>
#include <memory>

#include "propulsion_estimator/common/data_error.h"

namespace propulsion_estimator {
namespace {

// What libcsv's callbacks fill in while one line is fed.
struct Collector {
  std::vector<std::string> fields;
  bool row_ended = false;
};

void onField(void* data, std::size_t length, void* collector) {
  static_cast<Collector*>(collector)->fields.emplace_back(static_cast<const char*>(data), length);
}

void onRowEnd(int, void* collector) { static_cast<Collector*>(collector)->row_ended = true; }

bool isBlank(const std::string& line) { return line.find_first_not_of(" \t") == std::string::npos; }

// Drops the empty fields a trailing delimiter leaves after the last named column.
void dropTrailingEmpty(std::vector<std::string>* fields, std::size_t keep) {
  while (fields->size() > keep && fields->back().empty()) fields->pop_back();
}

}  // namespace

CsvText splitCsvText(const std::string& text, const std::string& source) {
  CsvText table;
  table.source = source;
  std::size_t at = 0;
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    table.had_byte_order_mark = true;
    at = 3;
  }

  csv_parser parser;
  if (csv_init(&parser, CSV_STRICT | CSV_STRICT_FINI) != 0) throw DataError(source + ": cannot start the CSV parser");
  std::unique_ptr<csv_parser, void (*)(csv_parser*)> guard(&parser, csv_free);

  Collector collector;
  int line_number = 0;
  int row_line = 0;  // line where the row being collected started
  bool in_row = false;
  bool have_header = false;
  auto finishRow = [&]() {
    if (!have_header) {
      table.header = std::move(collector.fields);
      dropTrailingEmpty(&table.header, 0);
      table.header_line = row_line;
      have_header = true;
    } else {
      dropTrailingEmpty(&collector.fields, table.header.size());
      if (collector.fields.size() != table.header.size()) {
        throw DataError(source + ":" + std::to_string(row_line) + ": " + std::to_string(collector.fields.size()) +
                        " fields, the header has " + std::to_string(table.header.size()) + " columns");
      }
      table.rows.push_back({row_line, std::move(collector.fields)});
    }
    collector = Collector{};
    in_row = false;
  };

  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!in_row) {
      if (isBlank(line)) continue;
      const std::size_t first = line.find_first_not_of(" \t");
      if (line[first] == '#') {
        table.comments.push_back({line_number, line.substr(first + 1)});
        continue;
      }
      if (!have_header) {
        table.delimiter = line.find(';') != std::string::npos ? ';' : ',';
        csv_set_delim(&parser, static_cast<unsigned char>(table.delimiter));
      }
      row_line = line_number;
      in_row = true;
    }
    line.push_back('\n');
    if (csv_parse(&parser, line.data(), line.size(), onField, onRowEnd, &collector) != line.size()) {
      throw DataError(source + ":" + std::to_string(line_number) + ": " + csv_strerror(csv_error(&parser)) +
                      " (a quote inside an unquoted field, or text after a closing quote)");
    }
    if (collector.row_ended) finishRow();
  }
  if (in_row) {
    if (csv_fini(&parser, onField, onRowEnd, &collector) != 0) {
      throw DataError(source + ":" + std::to_string(row_line) +
                      ": a quoted field is not closed before the end of the file");
    }
    finishRow();
  }
  if (!have_header) throw DataError(source + ": empty file (no header line)");
  return table;
}

std::string cellWhere(const CsvText& table, int line, std::size_t column) {
  return table.source + ":" + std::to_string(line) + ": column " + std::to_string(column + 1) + " '" +
         table.header[column] + "'";
}

std::optional<double> parseDecimal(const std::string& field, bool decimal_comma) {
  std::string text = field;
  if (decimal_comma) {
    if (text.find('.') != std::string::npos) return std::nullopt;
    const std::size_t comma = text.find(',');
    if (comma != std::string::npos) text[comma] = '.';
  }
  // from_chars takes a '-' but not a '+'.
  const std::size_t start = !text.empty() && text[0] == '+' ? 1 : 0;
  if (start == 1 && text.size() > 1 && text[1] == '-') return std::nullopt;
  double value = 0.0;
  const char* first = text.data() + start;
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, value, std::chars_format::general);
  if (error != std::errc() || end != last || first == last) return std::nullopt;
  return value;
}

bool usesDecimalComma(const CsvText& table, const std::vector<std::size_t>& columns, DecimalSeparator separator) {
  if (separator != DecimalSeparator::kAuto) {
    if (separator == DecimalSeparator::kComma && table.delimiter == ',') {
      throw DataError(table.source + ": decimal commas were asked for, but the fields are separated by ','");
    }
    return separator == DecimalSeparator::kComma;
  }
  if (table.delimiter != ';') return false;
  for (const CsvText::Row& row : table.rows) {
    for (std::size_t column : columns) {
      if (row.fields[column].find(',') != std::string::npos) return true;
    }
  }
  return false;
}

std::optional<std::vector<double>> numericColumn(const CsvText& table, std::size_t column, bool decimal_comma) {
  std::vector<double> values;
  values.reserve(table.rows.size());
  const CsvText::Row* first_empty = nullptr;
  for (const CsvText::Row& row : table.rows) {
    const std::string& field = row.fields[column];
    if (field.empty()) {
      if (!first_empty) first_empty = &row;
      continue;
    }
    const std::optional<double> value = parseDecimal(field, decimal_comma);
    if (!value) {
      std::string why = "'" + field + "' is not a number";
      if (decimal_comma && field.find('.') != std::string::npos) why += " (this file uses decimal commas)";
      if (!decimal_comma && table.delimiter == ';' && field.find(',') != std::string::npos) {
        why += " (decimal points were asked for)";
      }
      throw DataError(cellWhere(table, row.line, column) + ": " + why);
    }
    if (!std::isfinite(*value)) {
      throw DataError(cellWhere(table, row.line, column) + ": '" + field + "' is not a finite number");
    }
    values.push_back(*value);
  }
  if (values.empty()) return std::nullopt;
  if (first_empty) {
    throw DataError(cellWhere(table, first_empty->line, column) + ": empty cell (the column has values in other rows)");
  }
  return values;
}

}  // namespace propulsion_estimator
