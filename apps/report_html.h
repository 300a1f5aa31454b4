#pragma once
// The pieces of `geohybrid report`'s HTML page: text escaped, images inlined as base64 data URIs
// (the page is one file, readable offline and attachable), tables.
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps::html
{
/// `text` with &, <, >, " and ' escaped.
std::string escaped(const std::string &text);

/// RFC 4648 base64 of `bytes`.
std::string base64(const std::string &bytes);

/// A <figure> holding `png` as a data URI, with `caption`. Throws std::runtime_error naming the
/// file if it cannot be read or is not a PNG.
std::string png_figure(const std::filesystem::path &png, const std::string &caption);

/// A <table> with a header row; every cell escaped. A row shorter than the header is padded.
std::string table(const std::vector<std::string> &header, const std::vector<std::vector<std::string>> &rows,
                  const std::string &css_class = "");

/// A collapsed block of preformatted text (an input file).
std::string details(const std::string &summary, const std::string &text);

/// details() of the whole text of `file` (a resolved input).
std::string file_details(const std::string &summary, const std::filesystem::path &file);

/// A number of a results CSV (sweep.csv, design.csv: 12 digits) to 4 for the page; an empty cell
/// (no value: a run that failed) stays empty.
std::string short_number(const std::string &cell);
} // namespace geohybrid::apps::html
