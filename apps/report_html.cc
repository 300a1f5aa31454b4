#include "report_html.h"

#include "run_directory.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps::html
{
std::string escaped(const std::string &text)
{
  std::string out;
  out.reserve(text.size());
  for (const char c : text)
    switch (c)
      {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&#39;"; break;
        default: out += c;
      }
  return out;
}

std::string base64(const std::string &bytes)
{
  static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve(4 * ((bytes.size() + 2) / 3));
  for (std::size_t k = 0; k < bytes.size(); k += 3)
    {
      const std::size_t n = std::min<std::size_t>(3, bytes.size() - k);
      unsigned int triple = 0;
      for (std::size_t j = 0; j < 3; ++j)
        triple = (triple << 8) | (j < n ? static_cast<unsigned char>(bytes[k + j]) : 0u);
      for (std::size_t j = 0; j < 4; ++j)
        out += j <= n ? alphabet[(triple >> (18 - 6 * j)) & 0x3f] : '=';
    }
  return out;
}

std::string png_figure(const std::filesystem::path &png, const std::string &caption)
{
  std::ifstream in(png, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0)
    throw std::runtime_error("report: '" + png.string() + "' cannot be read as a PNG image");
  return "<figure><img src=\"data:image/png;base64," + base64(bytes) + "\" alt=\"" + escaped(caption) +
         "\"><figcaption>" + escaped(caption) + "</figcaption></figure>\n";
}

std::string table(const std::vector<std::string> &header, const std::vector<std::vector<std::string>> &rows,
                  const std::string &css_class)
{
  std::string out = "<table" + (css_class.empty() ? std::string() : " class=\"" + css_class + "\"") + ">\n<thead><tr>";
  for (const std::string &cell : header)
    out += "<th>" + escaped(cell) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const std::vector<std::string> &row : rows)
    {
      out += "<tr>";
      for (std::size_t k = 0; k < std::max(row.size(), header.size()); ++k)
        out += "<td>" + (k < row.size() ? escaped(row[k]) : std::string()) + "</td>";
      out += "</tr>\n";
    }
  return out + "</tbody></table>\n";
}

std::string details(const std::string &summary, const std::string &text)
{
  return "<details><summary>" + escaped(summary) + "</summary><pre>" + escaped(text) + "</pre></details>\n";
}

std::string file_details(const std::string &summary, const std::filesystem::path &file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return details(summary, text.str());
}

std::string short_number(const std::string &cell) { return cell.empty() ? cell : number(std::stod(cell), 4); }
} // namespace geohybrid::apps::html
