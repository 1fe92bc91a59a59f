#include <pantocat/io/json_writer.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace pantocat
{
namespace
{
using Json = nlohmann::ordered_json;

/**
 * @p x as a JSON number of 12 significant digits (the precision summary.json
 * has always had): null if not finite, an integer if the rounded value is
 * integral and below 10^12 (as a 12-digit %g prints it), else the rounded
 * double, which the library writes in its shortest round-trip form.
 */
Json number(const double x)
{
  if (!std::isfinite(x))
    return nullptr;
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", x);
  const double rounded = std::strtod(text, nullptr);
  if (rounded == std::trunc(rounded) && std::abs(rounded) < 1e12)
    return static_cast<std::int64_t>(rounded);
  return rounded;
}
} // namespace

struct JsonWriter::Document
{
  Json root;
  /// The open objects and arrays, innermost last. Only the innermost one
  /// grows, so pointers to the outer ones stay valid.
  std::vector<Json*> open;

  /// Adds @p item to the innermost open scope (under @p key in an object).
  Json& add(const std::string& key, Json item)
  {
    if (open.empty())
      return root = std::move(item);
    Json& scope = *open.back();
    if (scope.is_array())
    {
      scope.push_back(std::move(item));
      return scope.back();
    }
    return scope[key] = std::move(item);
  }
};

JsonWriter::JsonWriter(std::ostream& out)
    : out(out), document(std::make_unique<Document>())
{
}

JsonWriter::~JsonWriter() = default;

void JsonWriter::close()
{
  if (document->open.empty())
    throw std::logic_error("JsonWriter: end_object or end_array without a begin");
  document->open.pop_back();
  if (document->open.empty())
    out << document->root.dump(2, ' ', false, Json::error_handler_t::replace) << '\n';
}

JsonWriter& JsonWriter::begin_object(const std::string& key)
{
  document->open.push_back(&document->add(key, Json::object()));
  return *this;
}

JsonWriter& JsonWriter::end_object()
{
  close();
  return *this;
}

JsonWriter& JsonWriter::begin_array(const std::string& key)
{
  document->open.push_back(&document->add(key, Json::array()));
  return *this;
}

JsonWriter& JsonWriter::end_array()
{
  close();
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const double x)
{
  document->add(key, number(x));
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const std::string& text)
{
  document->add(key, text);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const char* text)
{
  return value(key, std::string(text));
}

JsonWriter& JsonWriter::value(const std::string& key, const bool flag)
{
  document->add(key, flag);
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& key, const unsigned long n)
{
  document->add(key, n);
  return *this;
}

JsonWriter& JsonWriter::null(const std::string& key)
{
  document->add(key, nullptr);
  return *this;
}

JsonWriter& JsonWriter::intervals(const std::string& key,
                                  const std::vector<std::pair<double, double>>& list)
{
  Json pairs = Json::array();
  for (const auto& [begin, end] : list)
    pairs.push_back(Json::array({number(begin), number(end)}));
  document->add(key, std::move(pairs));
  return *this;
}
} // namespace pantocat
