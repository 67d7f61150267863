// The checks every reader makes before it opens an input, and those of every YAML document.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "ins/input_file.hpp"
#include "ins/yaml_checks.hpp"
#include "tests/support/error_message.hpp"

namespace deepnav {
namespace {

using testing::error_of;

TEST(InputFile, RegularFilesOnlyAndWithinTheSizeLimit) {
  const auto dir = std::filesystem::path(DEEPNAV_BINARY_DIR) / "input_checks_test";
  std::filesystem::create_directories(dir);
  const auto file = (dir / "small.txt").string();
  std::ofstream(file) << "twelve bytes";
  EXPECT_EQ(error_of([&] { check_input_file(file, "test file"); }), "");
  EXPECT_EQ(error_of([&] { check_input_file(file, "test file", 12); }), "");
  EXPECT_NE(error_of([&] { check_input_file(file, "test file", 11); }).find("is 12 bytes, more than the 11"),
            std::string::npos);
  EXPECT_NE(error_of([&] { check_input_file(dir.string(), "test file"); }).find("is a directory"), std::string::npos);
  EXPECT_NE(
      error_of([] { check_input_file("/dev/zero", "scenario file"); }).find("scenario file '/dev/zero' is a device"),
      std::string::npos);
  EXPECT_NE(error_of([&] { check_input_file((dir / "missing").string(), "test file"); }).find("No such file"),
            std::string::npos);
  // A FIFO without a writer: an error at once, where opening it would block forever.
  const auto fifo = (dir / "fifo").string();
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(error_of([&] { check_input_file(fifo, "sample file"); }).find("is a FIFO"), std::string::npos);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  std::filesystem::remove(fifo);
}

TEST(YamlChecks, DuplicateKeysAnywhereAreErrors) {
  auto load = [](const char* text) { return [text] { load_checked_yaml(text, "x.yaml"); }; };
  EXPECT_EQ(error_of(load("a: 1\nb: {c: 2, d: 3}\ne: [{f: 1}, {f: 2}]\n")), "");
  EXPECT_EQ(error_of(load("a: 1\nb: 2\na: 3\n")), "x.yaml:3: key 'a' appears twice in one mapping (lines 1 and 3)");
  EXPECT_EQ(error_of(load("top:\n  k: 1\n  k: 2\n")), "x.yaml:3: key 'k' appears twice in one mapping (lines 2 and 3)");
  EXPECT_EQ(error_of(load("l:\n  - {x: 1, x: 2}\n")), "x.yaml:2: key 'x' appears twice in one mapping (lines 2 and 2)");
  // An alias of a scalar used as a key is that key.
  EXPECT_EQ(error_of(load("a: &k x\nm:\n  x: 1\n  *k : 2\n")),
            "x.yaml:4: key 'x' appears twice in one mapping (lines 3 and 4)");
  EXPECT_EQ(error_of(load("~: 1\nb: 2\nnull: 3\n")),
            "x.yaml:3: the empty (null) key appears twice in one mapping (lines 1 and 3)");
  // Two different keys that are collections are not text and are not compared.
  EXPECT_EQ(error_of(load("? [a]\n: 1\n? [b]\n: 2\n")), "");
}

TEST(YamlChecks, AliasesAreCountedNotFollowed) {
  // Aliases that repeat a few blocks load as yaml-cpp gives them.
  const YAML::Node ok = load_checked_yaml("base: &b {x: 1, y: [1, 2]}\none: *b\ntwo: *b\n", "x.yaml");
  EXPECT_EQ(ok["two"]["y"][1].as<int>(), 2);
  // Ten aliases of ten aliases, eleven levels: the check that followed aliases ran for hours.
  std::string laughs = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 11; ++level) {
    laughs += fmt::format("a{}: &a{} [", level, level);
    for (int k = 0; k < 10; ++k) laughs += fmt::format("{}*a{}", k ? ", " : "", level - 1);
    laughs += "]\n";
  }
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(error_of([&] { load_checked_yaml(laughs, "laughs.yaml"); }),
            "laughs.yaml:5: the aliases repeat more than 100000 nodes (alias '*a3' alone repeats 11111): nested "
            "aliases that multiply are refused");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  // Up to the limit in all, aliases are fine: a list and its 99,999 items repeated once.
  std::string list = "a: &a [0";
  for (int k = 1; k < 99999; ++k) list += ", 0";
  EXPECT_EQ(error_of([&] { load_checked_yaml(list + "]\nb: *a\n", "x.yaml"); }), "");
  EXPECT_NE(error_of([&] {
              load_checked_yaml(list + "]\nb: *a\nc: [1, *a]\n", "x.yaml");
            }).find("x.yaml:3: the aliases repeat more than 100000 nodes (alias '*a' alone repeats 100000)"),
            std::string::npos);
  std::string many = "a: &a [1, 2, 3, 4, 5, 6, 7, 8, 9]\nb: [";
  for (int k = 0; k < 10001; ++k) many += k ? ", *a" : "*a";
  EXPECT_EQ(error_of([&] { load_checked_yaml(many + "]\n", "many.yaml"); }),
            "many.yaml:2: the aliases repeat more than 100000 nodes (alias '*a' alone repeats 10): nested aliases "
            "that multiply are refused");
  // An alias inside the node it names makes a document without end.
  EXPECT_EQ(error_of([] { load_checked_yaml("a: &a [1, *a]\n", "loop.yaml"); }),
            "loop.yaml:1: alias '*a' is inside the node it names: the document would never end");
  EXPECT_EQ(error_of([] { load_checked_yaml("a: &a\n  b: {c: *a}\n", "loop.yaml"); }),
            "loop.yaml:2: alias '*a' is inside the node it names: the document would never end");
}

TEST(YamlChecks, ControlCharactersAreErrorsOnTheirLine) {
  // yaml-cpp reported a NUL as an unknown escape character one line further down.
  EXPECT_EQ(error_of([] { load_checked_yaml(std::string("input: a.bin\nout: out/x\0\nfs: 1\n", 28), "nul.yaml"); }),
            "nul.yaml:2: a NUL byte at column 11: YAML text holds no control characters (is it a binary file?)");
  EXPECT_EQ(error_of([] { load_checked_yaml("a: 1\r\nb: \x07\n", "bell.yaml"); }),
            "bell.yaml:2: control character 0x07 at column 4: YAML text holds no control characters (is it a binary "
            "file?)");
  EXPECT_EQ(error_of([] { load_checked_yaml("a:\t1\r\n", "tab.yaml"); }), "");
  // UTF-16 text (which yaml-cpp reads) holds zero bytes that are no NUL characters.
  std::string utf16 = "\xFF\xFE";
  for (const char c : std::string("a: 1\nb: 2\n")) utf16 += std::string{c, '\0'};
  EXPECT_EQ(load_checked_yaml(utf16, "utf16.yaml")["b"].as<int>(), 2);
}

}  // namespace
}  // namespace deepnav
