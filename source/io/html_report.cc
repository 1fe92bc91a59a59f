#include <pantocat/base/number_format.h>
#include <pantocat/io/html_report.h>

#include <cmath>
#include <regex>

namespace pantocat
{
std::string html_escape(const std::string& text)
{
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text)
    switch (c)
    {
    case '&':
      escaped += "&amp;";
      break;
    case '<':
      escaped += "&lt;";
      break;
    case '>':
      escaped += "&gt;";
      break;
    case '"':
      escaped += "&quot;";
      break;
    default:
      escaped += c;
    }
  return escaped;
}

std::string inline_svg(const std::string& svg, const std::string& prefix,
                       const std::string& title)
{
  const std::size_t begin = svg.find("<svg");
  const std::size_t end = svg.rfind("</svg>");
  if (begin == std::string::npos || end == std::string::npos || end < begin)
    return "";
  std::string s = svg.substr(begin, end + 6 - begin);
  s = std::regex_replace(s, std::regex(R"((\sid=)(['"]))"), "$1$2" + prefix);
  s = std::regex_replace(s, std::regex(R"((href=)(['"])#)"), "$1$2#" + prefix);
  s = std::regex_replace(s, std::regex(R"(url\(#)"), "url(#" + prefix);
  const std::size_t t0 = s.find("<title>"), t1 = s.find("</title>");
  const std::string own_title = "<title>" + html_escape(title) + "</title>";
  if (t0 != std::string::npos && t1 != std::string::npos && t0 < t1)
    s.replace(t0, t1 + 8 - t0, own_title);
  else
    s.insert(s.find('>') + 1, own_title);
  return s;
}

namespace
{
/// The page's look: plain, printable, no resource from elsewhere.
constexpr const char* style = R"(
body { font-family: sans-serif; max-width: 1250px; margin: 1em auto; padding: 0 1em;
       color: #202020; line-height: 1.4; }
h1 { font-size: 1.5em; border-bottom: 2px solid #0060c0; padding-bottom: 0.2em; }
h2 { font-size: 1.2em; margin-top: 1.6em; color: #004080; }
h3 { font-size: 1.05em; }
table { border-collapse: collapse; margin: 0.5em 0 1em 0; }
th, td { border: 1px solid #c0c8d0; padding: 0.2em 0.6em; text-align: left; }
th { background: #e8eef6; }
td.number { text-align: right; font-variant-numeric: tabular-nums; }
td.pass { color: #006000; font-weight: bold; }
td.fail { color: #b00000; font-weight: bold; }
p.note { font-size: 0.85em; color: #606060; }
figure { margin: 1em 0; }
figure svg { max-width: 100%; height: auto; }
figcaption { font-size: 0.9em; color: #404040; }
)";
} // namespace

HtmlReport::HtmlReport(const std::string& title) : title(title)
{
  body = "<h1>" + html_escape(title) + "</h1>\n";
}

HtmlReport& HtmlReport::heading(const std::string& text, const unsigned int level,
                                const std::string& id)
{
  const std::string h = "h" + std::to_string(level);
  body += "<" + h + (id.empty() ? "" : " id=\"" + html_escape(id) + "\"") + ">" +
          html_escape(text) + "</" + h + ">\n";
  return *this;
}

HtmlReport& HtmlReport::paragraph(const std::string& text)
{
  body += "<p>" + html_escape(text) + "</p>\n";
  return *this;
}

HtmlReport& HtmlReport::note(const std::string& text)
{
  body += "<p class=\"note\">" + html_escape(text) + "</p>\n";
  return *this;
}

HtmlReport& HtmlReport::list(const std::vector<std::string>& items)
{
  body += "<ul>\n";
  for (const std::string& item : items)
    body += "<li>" + html_escape(item) + "</li>\n";
  body += "</ul>\n";
  return *this;
}

HtmlReport& HtmlReport::table(const std::vector<std::string>& header,
                              const std::vector<std::vector<Cell>>& rows,
                              const std::string& id)
{
  body += "<table" + (id.empty() ? std::string() : " id=\"" + html_escape(id) + "\"") +
          ">\n<tr>";
  for (const std::string& h : header)
    body += "<th>" + html_escape(h) + "</th>";
  body += "</tr>\n";
  for (const std::vector<Cell>& row : rows)
  {
    body += "<tr>";
    for (const Cell& c : row)
      body += (c.css_class.empty() ? std::string("<td>")
                                   : "<td class=\"" + html_escape(c.css_class) + "\">") +
              html_escape(c.text) + "</td>";
    body += "</tr>\n";
  }
  body += "</table>\n";
  return *this;
}

HtmlReport& HtmlReport::figure(const std::string& svg, const std::string& caption)
{
  const std::string prefix = "f" + std::to_string(++figures) + "-";
  body += "<figure>\n" + inline_svg(svg, prefix, caption) + "\n<figcaption>" +
          html_escape(caption) + "</figcaption>\n</figure>\n";
  return *this;
}

std::string HtmlReport::str() const
{
  return "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n"
         "<head>\n<meta charset=\"utf-8\"/>\n<title>" +
         html_escape(title) + "</title>\n<style>" + style +
         "</style>\n</head>\n<body>\n" + body + "</body>\n</html>\n";
}
HtmlReport::Cell HtmlReport::number(const double value, const int digits)
{
  return {std::isfinite(value) ? number_to_string(value, digits) : "-", "number"};
}
} // namespace pantocat
