// `lwcport lsp` on a stream a client got wrong: after each framing error (a Content-Length that is
// not a number, less or more than its message, too large; binary junk) the server resynchronises,
// reads the broken message where its bytes are one, says what it dropped, and answers every later
// request as it would have without the error.
#include <gtest/gtest.h>

#include <random>

#include <nlohmann/json.hpp>

#include "cli/lsp_client.h"
#include "support.h"

namespace lwc {
namespace {

using nlohmann::json;
using namespace lsp_client;

const std::string kUri = "file:///lsp-framing/a.vert";
const std::string kText = "#version 300 es\nuniform mat4 modelMatrix;\nin vec3 position;\n"
                          "void main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";

json hover_at_finding(int id) {
  return request(id, "textDocument/hover", {{"textDocument", {{"uri", kUri}}}, {"position", {{"line", 1}, {"character", 15}}}});
}

// The body of a hover request with id 5: what the broken frames below carry.
const std::string kBroken = hover_at_finding(5).dump();

struct Outcome {
  Session session;
  std::string log;
};

// initialize, the document opened, `broken`, then three requests (a hover on the document's
// finding, its code actions, shutdown) and exit, through `lwcport lsp --log`.
Outcome serve_around(const std::string& broken) {
  std::string dir = test::scratch("lsp-framing");
  json range = {{"start", {{"line", 1}, {"character", 0}}}, {"end", {{"line", 2}, {"character", 0}}}};
  std::string input = frame(initialize()) +
                      frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", kUri}, {"languageId", "glsl"}, {"version", 1}, {"text", kText}}}})) +
                      broken + frame(hover_at_finding(11)) +
                      frame(request(12, "textDocument/codeAction", {{"textDocument", {{"uri", kUri}}}, {"range", range}, {"context", {{"diagnostics", json::array()}}}})) +
                      frame(request(13, "shutdown")) + frame(notification("exit"));
  Session s = serve(input, "--log " + dir + "/server.log");
  return {s, test::read(dir + "/server.log")};
}

// What the three requests get on a sound stream.
const Session& sound() {
  static const Session s = serve_around("").session;
  return s;
}

// The three requests after the broken part are answered as on a sound stream, and the session
// ends with `exit` after `shutdown` (exit code 0): nothing after the error was lost.
void expect_three_answered(const Session& s) {
  EXPECT_EQ(s.exit_code, 0);
  for (int id : {11, 12, 13}) {
    const json* got = reply_to(s, id);
    const json* want = reply_to(sound(), id);
    ASSERT_NE(want, nullptr);
    ASSERT_NE(got, nullptr) << id;
    EXPECT_EQ(*got, *want) << id;
  }
  EXPECT_NE(reply_to(sound(), 11)->at("result").dump().find("lwc-uniform-world-float"), std::string::npos);
  EXPECT_FALSE(reply_to(sound(), 12)->at("result").empty());
}

// The broken message was read after all: request 5 has the hover's answer, and the client and
// the log are told what was wrong with its framing.
void expect_read_despite(const Outcome& o, const std::string& problem) {
  const json* five = reply_to(o.session, 5);
  ASSERT_NE(five, nullptr);
  EXPECT_EQ((*five)["result"], (*reply_to(sound(), 11))["result"]);
  bool told = false;
  for (const json& m : notifications(o.session, "window/logMessage"))
    told |= m["type"] == 2 && m["message"].get<std::string>().find(problem) != std::string::npos;
  EXPECT_TRUE(told) << problem;
  EXPECT_NE(o.log.find(problem), std::string::npos) << o.log;
  for (const json& m : o.session.messages) EXPECT_FALSE(m.contains("error") && m["error"]["code"] == -32700) << m.dump();
}

TEST(LanguageServerFraming, AContentLengthThatIsNotANumber) {
  for (std::string before : {"", "\r\n"}) {  // the message right after the header, or after a line end
    Outcome o = serve_around("Content-Length: twelve\r\n\r\n" + before + kBroken);
    expect_three_answered(o.session);
    expect_read_despite(o, "its Content-Length \"twelve\" is not a number");
  }
}

TEST(LanguageServerFraming, AContentLengthLessThanTheMessage) {
  Outcome o = serve_around("Content-Length: 20\r\n\r\n" + kBroken);
  expect_three_answered(o.session);
  expect_read_despite(o, "its Content-Length (20) was less than its " + std::to_string(kBroken.size()) + " bytes");
}

TEST(LanguageServerFraming, AContentLengthMoreThanTheMessage) {
  // 30 bytes more: the next message's header and part of its body are read into this one's.
  Outcome o = serve_around("Content-Length: " + std::to_string(kBroken.size() + 30) + "\r\n\r\n" + kBroken);
  expect_three_answered(o.session);
  expect_read_despite(o, "its Content-Length (" + std::to_string(kBroken.size() + 30) + ") was more than its " + std::to_string(kBroken.size()) + " bytes");
}

TEST(LanguageServerFraming, AContentLengthThatOverflows) {
  for (std::string length : {"99999999999999999999999999", "18446744073709551616", "4294967296"}) {
    Outcome o = serve_around("Content-Length: " + length + "\r\n\r\n" + kBroken);
    expect_three_answered(o.session);
    expect_read_despite(o, "its Content-Length (" + length + ") is more than the 256 MB a message may have");
  }
}

// A Content-Length that ends inside the next message's header ("{" and "Content-Length" of the
// next header, here): that header is read as a header, so the next message is not lost. (Found by
// the fuzzer: tests/fuzz/lsp-regressions.)
TEST(LanguageServerFraming, AContentLengthThatCutsTheNextHeaderInTwo) {
  for (int cut : {1, 7, 14, 15}) {  // "C", "Content", "Content-Length", "Content-Length:" after the "{"
    Outcome o = serve_around("Content-Length: " + std::to_string(1 + cut) + "\r\n\r\n{");
    expect_three_answered(o.session);
  }
}

// Binary junk (every byte value, line ends and colons among them) is dropped with one parse error,
// its size said to the client and in the log with its first bytes.
TEST(LanguageServerFraming, KilobytesOfBinaryJunk) {
  std::mt19937 random(38);
  std::string junk;
  for (int i = 0; i < 4096; ++i) junk += static_cast<char>(random() % 256);
  ASSERT_EQ(junk.find("ontent-"), std::string::npos);
  junk += "\r\n\r\nContent-Type: x\r\n:\r\n\r\n";
  Outcome o = serve_around(junk);
  expect_three_answered(o.session);
  int parse_errors = 0;
  for (const json& m : o.session.messages)
    if (m.contains("error") && m["error"]["code"] == -32700) {
      ++parse_errors;
      EXPECT_TRUE(m["id"].is_null());
      EXPECT_NE(m["error"]["message"].get<std::string>().find(std::to_string(junk.size()) + " bytes that are not a message were dropped"),
                std::string::npos) << m.dump();
    }
  EXPECT_EQ(parse_errors, 1);
  EXPECT_NE(o.log.find(std::to_string(junk.size()) + " bytes that are not a message were dropped"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("dropped: "), std::string::npos) << o.log;
}

// A message whose JSON is broken but framed right gets a parse error at once; a batch (an array)
// is an invalid request; neither loses what comes after.
TEST(LanguageServerFraming, BrokenJsonAndBatchesInSoundFrames) {
  Outcome o = serve_around("Content-Length: 7\r\n\r\n{\"a\":}}" + frame(json::array({hover_at_finding(6)})));
  expect_three_answered(o.session);
  std::vector<int> codes;
  for (const json& m : o.session.messages)
    if (m.contains("error") && m["id"].is_null()) codes.push_back(m["error"]["code"]);
  EXPECT_EQ(codes, (std::vector<int>{-32700, -32600}));
  EXPECT_EQ(reply_to(o.session, 6), nullptr);
}

// The input ends inside the last message (its Content-Length is more than what is left): it is
// read all the same, here `exit` after `shutdown`.
TEST(LanguageServerFraming, TheInputEndsInsideTheLastMessage) {
  std::string exit = notification("exit").dump();
  Session s = serve(frame(initialize()) + frame(request(2, "shutdown")) + "Content-Length: " + std::to_string(exit.size() + 100) + "\r\n\r\n" + exit);
  EXPECT_EQ(s.exit_code, 0);
}

// Headers as clients write them, sound if not by the letter: another header first, the name in
// any case, a space before the colon, bare line feeds, a line end between messages. Each message
// is read with no warning and no error.
TEST(LanguageServerFraming, HeadersAsClientsWriteThem) {
  std::string body = hover_at_finding(5).dump();
  std::string size = std::to_string(body.size());
  Outcome o = serve_around("Content-Type: application/vscode-jsonrpc; charset=utf-8\r\nContent-Length: " + size + "\r\n\r\n" + body +
                           "content-length:" + size + "\n\n" + hover_at_finding(6).dump() + "\r\n" +
                           "CONTENT-LENGTH : " + size + "\r\n\r\n" + hover_at_finding(7).dump());
  expect_three_answered(o.session);
  for (int id : {5, 6, 7}) ASSERT_NE(reply_to(o.session, id), nullptr) << id;
  for (const json& m : o.session.messages) {
    EXPECT_FALSE(m.contains("error")) << m.dump();
    EXPECT_NE(m.value("params", json::object()).value("type", 0), 2) << m.dump();
  }
}

// A client sends a message and waits for its answer: a message whose header is broken, or whose
// Content-Length is less than it, is answered once its last byte is here, not when the next
// message comes. (The wait for the answer is bounded, so a server that waits fails the test.)
TEST(LanguageServerFraming, ABrokenMessageIsAnsweredWithoutWaitingForTheNext) {
  for (std::string header : {"Content-Length: twelve\r\n\r\n", "Content-Length: 20\r\n\r\n"}) {
    std::string dir = test::scratch("lsp-framing-wait");
    test::write(dir + "/first", frame(initialize()) + header + request(5, "shutdown").dump());
    test::write(dir + "/then", frame(notification("exit")));
    test::write(dir + "/session.sh", "set -e\ncd " + dir + "\nmkfifo in\n" + test::binary() + " lsp < in > out &\nserver=$!\n"
                                     "exec 3> in\ncat first >&3\n"
                                     "for i in $(seq 200); do grep -qs '\"id\":5' out && break; sleep 0.05; done\n"
                                     "cp out answered\ncat then >&3\nexec 3>&-\nwait $server\n");
    test::Run r = test::run("bash " + dir + "/session.sh");
    EXPECT_EQ(r.exit_code, 0) << header;  // shutdown, then exit
    const json* five = reply_to({0, read_messages(test::read(dir + "/answered"))}, 5);
    ASSERT_NE(five, nullptr) << header;
    EXPECT_TRUE((*five)["result"].is_null());
  }
}

}  // namespace
}  // namespace lwc
