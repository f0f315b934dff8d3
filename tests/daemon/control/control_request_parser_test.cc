#include "daemon/control/control_request_parser.h"

#include <gtest/gtest.h>

#include <string>

namespace radfarm::daemon {
namespace {

std::span<const uint8_t> Bytes(const std::string& text) {
  return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

Result<ControlRequest> Parse(const std::string& text, uint64_t* attachment_bytes) {
  Result<nlohmann::json> json = ParseControlJson(Bytes(text));
  if (!json) return Error{json.error()};
  return ParseControlRequest(*json, attachment_bytes);
}

std::string ParseError(const std::string& text) {
  uint64_t attachment_bytes = 0;
  Result<ControlRequest> request = Parse(text, &attachment_bytes);
  EXPECT_FALSE(request.ok()) << text;
  return request.ok() ? "" : request.error();
}

TEST(ControlRequestParserTest, ReadsASubmitAndTheAttachmentItAnnounces) {
  uint64_t attachment_bytes = 0;
  Result<ControlRequest> request =
      Parse(R"({"command": "submit", "name": "box", "priority": -3, "attachment_bytes": 12})",
            &attachment_bytes);
  ASSERT_TRUE(request.ok()) << request.error();
  EXPECT_EQ(request->command, ControlCommand::kSubmit);
  EXPECT_EQ(request->name, "box");
  EXPECT_EQ(request->priority, -3);
  EXPECT_EQ(attachment_bytes, 12u);
}

TEST(ControlRequestParserTest, AnIdIsAnyUnsigned64BitNumber) {
  uint64_t attachment_bytes = 7;
  Result<ControlRequest> request =
      Parse(R"({"command": "status", "id": 18446744073709551615})", &attachment_bytes);
  ASSERT_TRUE(request.ok()) << request.error();
  EXPECT_EQ(request->id, 18446744073709551615u);
  EXPECT_EQ(attachment_bytes, 0u);
  EXPECT_EQ(ParseError(R"({"command": "status", "id": -1})"), "'id' must not be negative");
}

// Any bytes are answered with an error, never an exception that ends the daemon.
TEST(ControlRequestParserTest, BytesThatAreNotUtf8OrNotJsonAreAnError) {
  EXPECT_EQ(ParseError("{\"command\": \"submit\", \"name\": \"caf\xe9\", \"attachment_bytes\": 8}"),
            "the request is not valid JSON");
  EXPECT_EQ(ParseError(std::string("\xff\xfe\0{", 4)), "the request is not valid JSON");
  EXPECT_EQ(ParseError(R"({"command": "list"} {"command": "list"})"),
            "the request is not valid JSON");
  EXPECT_EQ(ParseError(""), "the request is not valid JSON");
}

TEST(ControlRequestParserTest, AnErrorNamingBadBytesIsStillSentAsUtf8) {
  // An unknown command is quoted in the error; its text on the wire replaces what is not UTF-8.
  nlohmann::json json = {{"command", "caf\xe9"}};
  uint64_t attachment_bytes = 0;
  Result<ControlRequest> request = ParseControlRequest(json, &attachment_bytes);
  ASSERT_FALSE(request.ok());
  EXPECT_EQ(
      JsonText(ControlError("bad_request", request.error()).body),
      "{\"code\":\"bad_request\",\"error\":\"unknown command 'caf\xef\xbf\xbd'\",\"ok\":false}");
}

// A priority of 2^64 - 1 read as a signed number was -1: accepted silently as the wrong value.
TEST(ControlRequestParserTest, AnIntegerArgumentPastInt64IsRefusedNotWrapped) {
  EXPECT_EQ(ParseError(R"({"command": "submit", "priority": 18446744073709551615,
                          "attachment_bytes": 1})"),
            "'priority' must be an integer in [-9223372036854775808, 9223372036854775807]");
  EXPECT_EQ(ParseError(R"({"command": "log", "limit": 18446744073709551615})"),
            "'limit' must be an integer in [-9223372036854775808, 9223372036854775807]");
}

TEST(ControlRequestParserTest, RefusesWrongShapesNamingTheKey) {
  EXPECT_EQ(ParseError("[1, 2]"), "a request must be a JSON object");
  EXPECT_EQ(ParseError(R"({"command": 3})"), "'command' must be a string");
  EXPECT_EQ(ParseError(R"({"command": "mystery"})"), "unknown command 'mystery'");
  EXPECT_EQ(ParseError(R"({"command": "log", "limit": 0})"), "'limit' must be in [1, 100000]");
  EXPECT_EQ(ParseError(R"({"command": "submit"})"),
            "submit needs the job bundle: 'attachment_bytes' must be an integer");
  EXPECT_EQ(ParseError(R"({"command": "submit", "attachment_bytes": 1073741825})"),
            "'attachment_bytes' must be in [1, 1073741824]");
  EXPECT_EQ(ParseError(R"({"command": "submit", "name": 1, "attachment_bytes": 1})"),
            "'name' must be a string");
}

}  // namespace
}  // namespace radfarm::daemon
