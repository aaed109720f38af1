#pragma once

#include <optional>
#include <string>
#include <vector>

namespace propulsion_estimator {

/// A delimited text table as a thrust-stand program writes it, split into its parts but not yet
/// interpreted: '#' comment lines, one header line of column names, and rows of text fields,
/// each with its line in the file. Quoting follows RFC 4180 (libcsv does the tokenizing).
struct CsvText {
  /// A '#' comment line: its line in the file and the text after the '#'.
  struct Line {
    int line = 0;  ///< line in the file, 1-based
    std::string text;  ///< the text
  };
  /// A row: its line in the file and its fields, as text.
  struct Row {
    int line = 0;  ///< line in the file, 1-based
    std::vector<std::string> fields;  ///< one per column
  };

  std::string source;  ///< the file it came from, for messages
  char delimiter = ',';  ///< ',' or ';'
  bool had_byte_order_mark = false;  ///< whether the file began with a UTF-8 byte-order mark
  std::vector<Line> comments;  ///< text after the '#', in file order
  int header_line = 0;  ///< the header's line in the file, 1-based
  std::vector<std::string> header;  ///< trailing empty names (a trailing delimiter) removed
  std::vector<Row> rows;            ///< as many fields as the header (a trailing empty field dropped)
};

/// Splits `text`: strips a UTF-8 byte-order mark, takes lines starting with '#' as comments and
/// skips blank lines; the first other line is the header. The delimiter is ';' when the header
/// line holds a ';', ',' otherwise. Throws DataError ("<source>: empty file (no header line)",
/// "<source>:<line>: 5 fields, the header has 4 columns", malformed quoting) naming the line.
CsvText splitCsvText(const std::string& text, const std::string& source);

/// "<source>:<line>: column <n> '<name>'" for messages about one cell.
std::string cellWhere(const CsvText& table, int line, std::size_t column);

/// Whether the numbers of a table use a decimal comma. Only a ';'-separated table can: it does when
/// one of its cells in `columns` holds a ',' (stand software writes no thousands separators).
enum class DecimalSeparator { kAuto, kPoint, kComma };
/// Whether `table`'s numbers use a decimal comma: as `separator` says, or for kAuto as detected
/// from the cells of `columns` (see DecimalSeparator).
bool usesDecimalComma(const CsvText& table, const std::vector<std::size_t>& columns, DecimalSeparator separator);

/// The values of one column as finite numbers; nullopt when every cell is empty (not logged).
/// Throws DataError naming the cell for an empty cell among values, text, NaN or infinity.
std::optional<std::vector<double>> numericColumn(const CsvText& table, std::size_t column, bool decimal_comma);

/// A decimal number in a cell: optional sign, digits, one decimal separator ('.' or, when
/// `decimal_comma`, ','), optional exponent. nullopt for anything else (text, hex, empty). NaN
/// and infinity parse (as "nan", "inf") so that the caller can name them.
std::optional<double> parseDecimal(const std::string& field, bool decimal_comma);

}  // namespace propulsion_estimator
