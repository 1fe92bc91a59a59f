#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * A JSON writer for summary.json with the shape of a streaming writer: open
 * objects and arrays, add values under keys (no key inside an array), close
 * them. The document is built as an nlohmann::ordered_json (keys in the order
 * given) and written to the stream, indented by two spaces, when the outermost
 * object or array is closed; every string is escaped by the library, so
 * names and messages with quotes, backslashes, control characters or bytes
 * that are not UTF-8 (replaced by U+FFFD) still give valid JSON. Numbers are
 * rounded to 12 significant digits (integral values below 10^12 are written
 * without a decimal point); non-finite numbers are written as null.
 */
class JsonWriter
{
public:
  explicit JsonWriter(std::ostream& out);
  ~JsonWriter();

  JsonWriter& begin_object(const std::string& key = "");
  JsonWriter& end_object();
  JsonWriter& begin_array(const std::string& key = "");
  JsonWriter& end_array();
  JsonWriter& value(const std::string& key, double number);
  JsonWriter& value(const std::string& key, const std::string& text);
  JsonWriter& value(const std::string& key, const char* text);
  JsonWriter& value(const std::string& key, bool flag);
  JsonWriter& value(const std::string& key, unsigned long number);
  /// null under @p key: a value that does not exist (e.g. no filter, no steady arm).
  JsonWriter& null(const std::string& key);
  /// [[t0, t1], ...]
  JsonWriter& intervals(const std::string& key,
                        const std::vector<std::pair<double, double>>& list);

private:
  /// The document under construction and its open objects and arrays.
  struct Document;

  /// Closes the innermost object or array; writes the document when it was the outermost.
  void close();

  std::ostream& out;
  std::unique_ptr<Document> document;
};
} // namespace pantocat
