#include "daemon/console/web/event_stream.h"

#include <gtest/gtest.h>

#include <thread>

namespace radfarm::web {
namespace {

std::string ReadSome(EventStream& stream, size_t max) {
  std::string out(max, '\0');
  out.resize(stream.Read(out.data(), max));
  return out;
}

// Reads until `text` has been read (or the stream ends).
std::string ReadThrough(EventStream& stream, const std::string& text) {
  std::string all;
  while (all.find(text) == std::string::npos) {
    const std::string piece = ReadSome(stream, 7);  // small reads: events span several
    if (piece.empty()) break;
    all += piece;
  }
  return all;
}

TEST(EventStreamTest, SendsTheLatestSnapshotThenEachNewOneAsAnEvent) {
  StatusBoard board;
  StatusSnapshot first;
  first.status_json = R"({"jobs":[1]})";
  board.Publish(first);
  EventStream stream(board);
  EXPECT_EQ(ReadThrough(stream, "[1]}\n\n"),
            "retry: 2000\n\nevent: status\ndata: {\"jobs\":[1]}\n\n");
  std::thread publisher([&] {
    StatusSnapshot second;
    second.status_json = R"({"jobs":[2]})";
    board.Publish(second);
  });
  EXPECT_EQ(ReadThrough(stream, "[2]}\n\n"), "event: status\ndata: {\"jobs\":[2]}\n\n");
  publisher.join();
}

TEST(EventStreamTest, EndsWhenTheBoardCloses) {
  StatusBoard board;
  EventStream stream(board);
  EXPECT_EQ(ReadThrough(stream, "\n\n"), "retry: 2000\n\n");
  std::thread closer([&] { board.Close(); });
  std::string rest;
  // Keep-alives may come first on a slow machine; the stream still ends.
  while (true) {
    const std::string piece = ReadSome(stream, 64);
    if (piece.empty()) break;
    rest += piece;
  }
  closer.join();
  EXPECT_EQ(rest.find("event:"), std::string::npos);
}

// A stream evicted while it waits for the next snapshot wakes at once (not at its keep-alive),
// tells the page when to come back, and ends.
TEST(EventStreamTest, AnEvictedStreamSendsALastEventAndEnds) {
  StatusBoard board;
  StreamSlots slots(board, 1, 1);
  EventStream old_stream(board, slots.Join("127.0.0.1"));
  EXPECT_EQ(ReadThrough(old_stream, "\n\n"), "retry: 2000\n\n");
  std::unique_ptr<StreamSlots::Ticket> newer;
  std::thread joiner([&] { newer = slots.Join("127.0.0.1"); });
  std::string rest;
  while (true) {
    const std::string piece = ReadSome(old_stream, 64);
    if (piece.empty()) break;
    rest += piece;
  }
  joiner.join();
  EXPECT_NE(rest.find("event: evicted\ndata: {\"retry_ms\":30000}\n\n"), std::string::npos);
  EXPECT_EQ(slots.size(), 1u);
}

}  // namespace
}  // namespace radfarm::web
