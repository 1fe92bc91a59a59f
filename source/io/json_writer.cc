#include <pantocat/io/json_writer.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
JsonWriter::JsonWriter(std::ostream& out) : out(out) {}

void JsonWriter::separator_and_key(const std::string& key)
{
  if (!first_in_scope.empty())
  {
    if (!first_in_scope.back())
      out << ',';
    first_in_scope.back() = false;
    out << '\n' << std::string(2 * depth(), ' ');
  }
  if (!key.empty())
    out << quoted(key) << ": ";
}

std::string JsonWriter::quoted(const std::string& text)
{
  std::string s = "\"";
  for (const char c : text)
  {
    if (c == '"' || c == '\\')
      s += '\\';
    if (c == '\n')
    {
      s += "\\n";
      continue;
    }
    s += c;
  }
  return s + "\"";
}

std::string JsonWriter::number(const double x) const
{
  if (!std::isfinite(x))
    return "null";
  std::ostringstream s;
  s.precision(12);
  s << x;
  return s.str();
}

JsonWriter& JsonWriter::begin_object(const std::string& key)
{
  separator_and_key(key);
  out << '{';
  first_in_scope.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object()
{
  first_in_scope.pop_back();
  out << '\n' << std::string(2 * depth(), ' ') << '}';
  if (first_in_scope.empty())
    out << '\n';
  return *this;
}

JsonWriter& JsonWriter::begin_array(const std::string& key)
{
  separator_and_key(key);
  out << '[';
  first_in_scope.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array()
{
  first_in_scope.pop_back();
  out << ']';
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const double x)
{
  separator_and_key(key);
  out << number(x);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const std::string& text)
{
  separator_and_key(key);
  out << quoted(text);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const char* text)
{
  return value(key, std::string(text));
}

JsonWriter& JsonWriter::value(const std::string& key, const bool flag)
{
  separator_and_key(key);
  out << (flag ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const unsigned long n)
{
  separator_and_key(key);
  out << n;
  return *this;
}

JsonWriter& JsonWriter::intervals(const std::string& key,
                                  const std::vector<std::pair<double, double>>& list)
{
  separator_and_key(key);
  out << '[';
  for (std::size_t i = 0; i < list.size(); ++i)
    out << (i ? ", " : "") << '[' << number(list[i].first) << ", "
        << number(list[i].second) << ']';
  out << ']';
  return *this;
}
} // namespace pantocat
