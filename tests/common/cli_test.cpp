// The command line every relplane executable parses through cli::Parser: exit codes, checks and
// the one-line errors users see.
#include "relplane/common/cli.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace relplane::cli {
namespace {

// Parses `args` (without the program name); returns Parse's result and what it printed.
struct Outcome {
  std::optional<int> code;
  std::string out;
  std::string err;
};

Outcome ParseArgs(Parser& parser, std::vector<std::string> args) {
  args.insert(args.begin(), "relplane-test");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  Outcome outcome;
  outcome.code = parser.Parse(static_cast<int>(argv.size()), argv.data());
  outcome.out = testing::internal::GetCapturedStdout();
  outcome.err = testing::internal::GetCapturedStderr();
  return outcome;
}

TEST(Cli, ParsesEveryKindOfValue) {
  Parser parser("test");
  std::string name;
  std::vector<std::string> files;
  double rate = 0.0;
  std::vector<double> rates;
  int count = 0;
  int64_t big = 0;
  bool flag = false;
  parser.Add("--name", &name, "");
  parser.Add("--rate", &rate, "");
  parser.Add("--rates", &rates, "").Delimiter(',');
  parser.Add("--count", &count, "");
  parser.Add("--big", &big, "");
  parser.AddFlag("--flag", &flag, "");
  parser.Add("files", &files, "");
  const Outcome o = ParseArgs(parser, {"--name", "x", "--rate", "2.5", "--rates", "30,60,0", "--count",
                                 "7", "--big", "5000000000", "--flag", "a.pcd", "b.pcd"});
  EXPECT_FALSE(o.code.has_value()) << o.err;
  EXPECT_EQ(name, "x");
  EXPECT_DOUBLE_EQ(rate, 2.5);
  EXPECT_EQ(rates, (std::vector<double>{30, 60, 0}));
  EXPECT_EQ(count, 7);
  EXPECT_EQ(big, 5000000000LL);
  EXPECT_TRUE(flag);
  EXPECT_EQ(files, (std::vector<std::string>{"a.pcd", "b.pcd"}));
}

TEST(Cli, HelpExitsZeroAndListsTheOptionsWithDefaults) {
  Parser parser("does a thing");
  CommonFlags flags;
  AddCommonFlags(parser, &flags);
  int frames = 300;
  parser.Add("--frames", &frames, "frames per run").ShowDefault();
  const Outcome o = ParseArgs(parser, {"--help"});
  ASSERT_EQ(o.code, 0);
  EXPECT_NE(o.out.find("does a thing"), std::string::npos);
  EXPECT_NE(o.out.find("--lcm-url"), std::string::npos);
  EXPECT_NE(o.out.find("300"), std::string::npos);  // the default is shown
  EXPECT_NE(o.out.find("info"), std::string::npos);  // --log-level's default
}

TEST(Cli, UsageErrorsAreOneLineAndExitTwo) {
  Parser parser("test");
  double rate = 1.0;
  parser.Add("--rate", &rate, "").NonNegative();
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--rate", "-1"}, {"--rate", "5x"}, {"--bogus"}}) {
    const Outcome o = ParseArgs(parser, args);
    EXPECT_EQ(o.code, kExitConfig) << args[0];
    EXPECT_EQ(o.err.find('\n'), o.err.size() - 1) << o.err;  // one line
    EXPECT_NE(o.err.find("(see --help)"), std::string::npos);
  }
  EXPECT_DOUBLE_EQ(rate, 1.0);
}

TEST(Cli, NumberChecksSayWhatIsWanted) {
  Parser parser("test");
  double rate = 0.0;
  int loops = 1;
  double minutes = 1.0;
  parser.Add("--rate", &rate, "").NonNegative();
  parser.Add("--loop", &loops, "").Positive();
  parser.Add("--minutes", &minutes, "").Range(0.1, 600.0);
  EXPECT_NE(ParseArgs(parser, {"--rate", "-0.5"}).err.find("'-0.5' must be a number >= 0"),
            std::string::npos);
  EXPECT_NE(ParseArgs(parser, {"--loop", "0"}).err.find("'0' must be a number > 0"), std::string::npos);
  EXPECT_EQ(ParseArgs(parser, {"--minutes", "700"}).code, kExitConfig);
  EXPECT_FALSE(ParseArgs(parser, {"--rate", "0", "--loop", "2", "--minutes", "600"}).code.has_value());
  EXPECT_EQ(loops, 2);
}

TEST(Cli, RequiredAndExistingFileAreEnforced) {
  Parser parser("test");
  std::string scenario;
  parser.Add("scenario", &scenario, "").Required().ExistingFile();
  EXPECT_EQ(ParseArgs(parser, {}).code, kExitConfig);
  EXPECT_EQ(ParseArgs(parser, {"/no/such/file.yaml"}).code, kExitConfig);
  EXPECT_FALSE(ParseArgs(parser, {RELPLANE_SOURCE_DIR "/CMakeLists.txt"}).code.has_value());
}

TEST(Cli, OneValuePerUseLetsAPositionalFollow) {
  // relplane-launch --set a=1 --set b=2 SCENARIO: the scenario must not become a third --set.
  Parser parser("test");
  std::vector<std::string> sets;
  std::string scenario;
  parser.Add("scenario", &scenario, "");
  parser.Add("--set", &sets, "").OneValuePerUse();
  const Outcome o = ParseArgs(parser, {"--set", "a=1", "--set", "b=2", "office.yaml"});
  ASSERT_FALSE(o.code.has_value()) << o.err;
  EXPECT_EQ(sets, (std::vector<std::string>{"a=1", "b=2"}));
  EXPECT_EQ(scenario, "office.yaml");
}

}  // namespace
}  // namespace relplane::cli
