// The command line as a library (host/app/command_line.hpp): options by name become the verb's
// command line, usage errors one InputError; and a progress listener takes a Progress's updates.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "host/app/command_line.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"

using namespace binpick;
using namespace binpick::cli;

namespace {

using Line = std::vector<std::string>;
using Values = std::vector<std::string>;

Line line_of(const std::string& verb, const std::vector<NamedOption>& options) {
  const auto app = make_app();
  return command_line_of(*app, verb, options);
}

// The message of the InputError line_of throws ("" if none).
std::string refusal(const std::string& verb, const std::vector<NamedOption>& options) {
  try {
    line_of(verb, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CommandLine, OptionsByNameBecomeTheVerbsCommandLine) {
  EXPECT_EQ(line_of("synth", {{"model", Values{"builtin:bolt"}}, {"max_wall_seconds", Values{"2.5"}}}),
            (Line{"synth", "--model", "builtin:bolt", "--max-wall-seconds", "2.5"}));
  // A flag: on is its name, off its negation where it has one, else nothing (off by default).
  EXPECT_EQ(line_of("detect", {{"prerank", false}, {"verbose", true}, {"verbose", false}}),
            (Line{"detect", "--no-prerank", "--verbose"}));
  EXPECT_EQ(line_of("eval", {{"no_vsd", true}}), (Line{"eval", "--no-vsd"}));
  // Values an option takes together follow it once; several --model are one option's values.
  EXPECT_EQ(line_of("synth", {{"range", Values{"300", "3000"}}}),
            (Line{"synth", "--range", "300", "3000"}));
  EXPECT_EQ(line_of("detect", {{"model", Values{"a.ppfm", "b.ppfm"}}}),
            (Line{"detect", "--model", "a.ppfm", "b.ppfm"}));
}

TEST(CommandLine, UnknownVerbsAndOptionsAndWrongKindsAreRefused) {
  EXPECT_EQ(refusal("bake", {}), "binpick has no verb 'bake'");
  EXPECT_EQ(refusal("synth", {{"nope", Values{"1"}}}), "binpick synth has no option --nope");
  EXPECT_NE(refusal("synth", {{"bins", true}}).find("a value expected"), std::string::npos);
  EXPECT_NE(refusal("detect", {{"verbose", Values{"1"}}}).find("a flag"), std::string::npos);
}

TEST(CommandLine, AUsageErrorIsOneInputErrorAndHelpRunsNothing) {
  auto app = make_app();
  try {
    run_command_line(*app, {"synth", "--bins", "x"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--bins"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(see binpick VERB --help)"), std::string::npos);
  }
  testing::internal::CaptureStdout();
  EXPECT_FALSE(run_command_line(*make_app(), {"eval", "--help"}));
  EXPECT_NE(testing::internal::GetCapturedStdout().find("Usage: binpick eval"), std::string::npos);
}

TEST(Progress, AListenerTakesEveryUpdateAndTheSummaryWhileItLives) {
  std::vector<std::string> seen;
  {
    const ScopedProgressListener listener([&](const ProgressEvent& e) {
      seen.push_back(std::string(e.label) + " " + std::to_string(e.done) + "/" +
                     std::to_string(e.total) + " " + std::string(e.status) +
                     (e.finished ? " finished" : ""));
    });
    Progress p("work", 3);
    p.update(1, "a");
    p.update(2, "b");
    p.finish("all done");
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"work 1/3 a", "work 2/3 b", "work 3/3 all done finished"}));
  Progress after("other", 1);  // the listener is gone: nothing more reaches it
  after.update(1);
  EXPECT_EQ(seen.size(), 3u);
}

}  // namespace
