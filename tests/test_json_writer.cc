// summary.json through JsonWriter (nlohmann::ordered_json): any string, with
// every control character, quotes, backslashes or bytes that are not UTF-8,
// gives a document that a JSON parser reads back with the same strings, keys
// in the order written, and numbers at 12 significant digits.
#include <pantocat/io/json_writer.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

using namespace pantocat;

namespace
{
/// Every control character 0x01 ... 0x1f, with a quote and a backslash among them.
std::string control_characters()
{
  std::string text = "name \"quoted\" \\ ";
  for (char c = 0x01; c < 0x20; ++c)
    text += c;
  return text + " end";
}

/// A summary-like document as run_dynamics writes it, with @p text in a
/// key, a value, an array element and the failure reason.
std::string summary_with(const std::string& text)
{
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object()
      .value("status", "failed")
      .value("reason", text)
      .value("time_step", 5e-5)
      .value("speed", 48.)
      .value("end_time", 0.2708333333333333)
      .value("unknowns", 1000ul)
      .value("stability_limit_explicit", std::numeric_limits<double>::quiet_NaN())
      .value("flag", true);
  json.begin_array("scene").value("", text).value("", "contact wire").end_array();
  json.begin_object("contact_force").value(text, 1.5).value("max", 264.6443).end_object();
  json.begin_array("dropper_slack_intervals")
      .intervals("", {})
      .intervals("", {{0.25415, 0.2605}})
      .end_array();
  json.end_object();
  return out.str();
}
} // namespace

TEST(JsonWriter, EveryControlCharacterGivesValidJson)
{
  const std::string text = control_characters();
  const std::string written = summary_with(text);
  nlohmann::ordered_json parsed;
  ASSERT_NO_THROW(parsed = nlohmann::ordered_json::parse(written)) << written;
  EXPECT_EQ(parsed["reason"], text);
  EXPECT_EQ(parsed["scene"][0], text);
  EXPECT_EQ(parsed["contact_force"][text], 1.5);
  // One line per entry: no raw control character (a newline included) in a string.
  for (const char c : written)
    EXPECT_TRUE(c == '\n' || static_cast<unsigned char>(c) >= 0x20)
        << "raw control character " << int(c) << " in\n"
        << written;
}

TEST(JsonWriter, KeysInOrderAndNumbersAsBefore)
{
  const auto parsed = nlohmann::ordered_json::parse(summary_with("x"));
  std::vector<std::string> keys;
  for (const auto& item : parsed.items())
    keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"status", "reason", "time_step", "speed",
                                            "end_time", "unknowns",
                                            "stability_limit_explicit", "flag", "scene",
                                            "contact_force", "dropper_slack_intervals"}));
  EXPECT_EQ(parsed["time_step"], 5e-5);
  EXPECT_TRUE(parsed["speed"].is_number_integer()); // 48, as a 12-digit %g writes it
  EXPECT_EQ(parsed["end_time"], 0.270833333333);    // 12 significant digits
  EXPECT_EQ(parsed["unknowns"], 1000);
  EXPECT_TRUE(parsed["stability_limit_explicit"].is_null()); // NaN
  EXPECT_EQ(parsed["flag"], true);
  EXPECT_EQ(parsed["dropper_slack_intervals"].dump(), "[[],[[0.25415,0.2605]]]");
  const std::string text = summary_with("x");
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"unknowns\": 1000"), std::string::npos) << text;
}

TEST(JsonWriter, BytesThatAreNotUtf8AreReplaced)
{
  const std::string written = summary_with("bad \xff\xfe bytes \xc3");
  nlohmann::json parsed;
  ASSERT_NO_THROW(parsed = nlohmann::json::parse(written)) << written;
  EXPECT_EQ(parsed["reason"], "bad \xEF\xBF\xBD\xEF\xBF\xBD bytes \xEF\xBF\xBD");
}

TEST(JsonWriter, NothingIsWrittenBeforeTheOutermostScopeCloses)
{
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object().value("status", "completed").begin_object("guards");
  EXPECT_TRUE(out.str().empty());
  json.end_object();
  EXPECT_TRUE(out.str().empty());
  json.end_object();
  EXPECT_EQ(out.str().back(), '\n');
  EXPECT_THROW(json.end_object(), std::logic_error);
}
