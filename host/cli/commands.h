// The subcommands of `vkray`. Each registers itself on the CLI11 app; its callback runs the command
// and stores the process exit code in `exitCode`. Failures are thrown as vkray::Error and printed
// once by main().
#pragma once

#include <CLI/CLI.hpp>

namespace vkray::cli {

void registerRenderCommand(CLI::App& app, int& exitCode);
void registerDevicesCommand(CLI::App& app, int& exitCode);
void registerCompareCommand(CLI::App& app, int& exitCode);
void registerGenCommand(CLI::App& app, int& exitCode);
void registerConvertCommand(CLI::App& app, int& exitCode);
void registerAssembleCommand(CLI::App& app, int& exitCode);
// The bench report records the command line that produced it.
void registerBenchCommand(CLI::App& app, int& exitCode, int argc, const char* const* argv);

}  // namespace vkray::cli
