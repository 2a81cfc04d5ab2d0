// Shared by the CLI tests: a vkray command line run in-process through the subcommands' CLI11
// registrations, as main() wires them (errors are thrown, not printed), with stdout captured.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/commands.h"

namespace vkray::test {

struct CliResult {
    int exitCode = -1;
    std::string stdoutText;
};

// `args` without the program name, e.g. {"compare", "a.png", "b.png"}. Registers the subcommands that
// need no device (compare, gen, convert, assemble).
inline CliResult runVkray(std::vector<std::string> args) {
    CLI::App app{"vkray"};
    app.require_subcommand(1);
    CliResult r;
    cli::registerCompareCommand(app, r.exitCode);
    cli::registerGenCommand(app, r.exitCode);
    cli::registerConvertCommand(app, r.exitCode);
    cli::registerAssembleCommand(app, r.exitCode);
    args.insert(args.begin(), "vkray");
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    testing::internal::CaptureStdout();
    try {
        app.parse(int(argv.size()), argv.data());
    } catch (...) {
        testing::internal::GetCapturedStdout();
        throw;
    }
    r.stdoutText = testing::internal::GetCapturedStdout();
    return r;
}

}  // namespace vkray::test
