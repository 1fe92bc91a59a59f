#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * A minimal streaming JSON writer for summary.json (Debian 12's Boost 1.74
 * has no Boost.JSON, and property_tree writes numbers as strings). Numbers
 * are written with 12 significant digits; non-finite numbers as null.
 */
class JsonWriter
{
public:
  explicit JsonWriter(std::ostream& out);

  JsonWriter& begin_object(const std::string& key = "");
  JsonWriter& end_object();
  JsonWriter& begin_array(const std::string& key = "");
  JsonWriter& end_array();
  JsonWriter& value(const std::string& key, double number);
  JsonWriter& value(const std::string& key, const std::string& text);
  JsonWriter& value(const std::string& key, const char* text);
  JsonWriter& value(const std::string& key, bool flag);
  JsonWriter& value(const std::string& key, unsigned long number);
  /// [[t0, t1], ...]
  JsonWriter& intervals(const std::string& key,
                        const std::vector<std::pair<double, double>>& list);

private:
  void separator_and_key(const std::string& key);
  static std::string quoted(const std::string& text);
  std::string number(double x) const;

  std::ostream& out;
  std::vector<bool> first_in_scope;
  unsigned int depth() const { return first_in_scope.size(); }
};
} // namespace pantocat
