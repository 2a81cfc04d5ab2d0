// vkray: command-line entry point. The one place errors become a message and an exit code.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
    CLI::App app{"vkray: a Vulkan compute ray tracer for studying acceleration structures"};
    app.set_version_flag("--version", VKRAY_VERSION);
    app.require_subcommand(1);
    int exitCode = 0;
    vkray::cli::registerRenderCommand(app, exitCode);
    vkray::cli::registerDevicesCommand(app, exitCode);
    vkray::cli::registerCompareCommand(app, exitCode);
    vkray::cli::registerGenCommand(app, exitCode);
    vkray::cli::registerBenchCommand(app, exitCode, argc, argv);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const vkray::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "error: out of host memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return exitCode;
}
