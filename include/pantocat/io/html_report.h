#pragma once

#include <string>
#include <vector>

namespace pantocat
{
/// @p text with &, <, > and " written as character references (HTML and XML text).
std::string html_escape(const std::string& text);

/**
 * The SVG picture @p svg (the text of an .svg file, as gnuplot writes it)
 * ready to stand inside an HTML page: the XML declaration dropped, every id
 * and every reference to one ("#id", url(#id)) prefixed with @p prefix, so
 * that several pictures in one page do not share ids, and its title set to
 * @p title. Empty if @p svg holds no <svg> element.
 */
std::string inline_svg(const std::string& svg, const std::string& prefix,
                       const std::string& title);

/**
 * A self-contained HTML page built part by part: no script, no style sheet
 * or picture from elsewhere (pictures are inline SVG), written as
 * well-formed XML (XHTML5 syntax) so that any browser shows it and an XML
 * parser can check it. Text arguments are escaped here; SVG is taken as it is.
 */
class HtmlReport
{
public:
  /// A page titled @p title (also its first heading).
  explicit HtmlReport(const std::string& title);

  /// A heading of level 2 (a section) or 3 (a subsection), with id @p id if given.
  HtmlReport& heading(const std::string& text, unsigned int level = 2,
                      const std::string& id = "");
  /// A paragraph of plain text.
  HtmlReport& paragraph(const std::string& text);
  /// A paragraph in small grey print (sources, notes).
  HtmlReport& note(const std::string& text);
  /// A list of plain-text items.
  HtmlReport& list(const std::vector<std::string>& items);

  /// A table cell: its text and an optional class ("pass", "fail", "number").
  struct Cell
  {
    std::string text;
    std::string css_class = "";
  };
  /// A number cell, right-aligned, with @p digits significant digits ("-" if not finite).
  static Cell number(double value, int digits = 5);
  /// A table with one header row; @p id names it (for tests and links).
  HtmlReport& table(const std::vector<std::string>& header,
                    const std::vector<std::vector<Cell>>& rows,
                    const std::string& id = "");
  /**
   * A figure: the SVG @p svg (the text of an .svg file) inline, ids prefixed
   * by "f<n>-", with @p caption; only the caption if @p svg is empty.
   */
  HtmlReport& figure(const std::string& svg, const std::string& caption);

  /// The page.
  std::string str() const;

private:
  std::string title;
  std::string body;
  unsigned int figures = 0;
};
} // namespace pantocat
