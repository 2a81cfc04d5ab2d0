// vkray: command-line entry point. The one place errors become a message and an exit code: one
// "error: " line on stderr, exit 2 for a wrong command line (usage), 1 for everything else.
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <vulkan/vulkan.hpp>

#include "accel/accel_spec.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/suggest.h"
#include "gpu/driver_filter.h"

namespace {

constexpr int kUsageExit = 2;

// --help as CLI11 writes it, less its "Needs:" and "Excludes:" lists, which would push the
// descriptions off the line: a wrong combination is refused with its reason anyway.
class HelpFormatter : public CLI::Formatter {
public:
    std::string make_option_opts(const CLI::Option* opt) const override {
        if (opt->get_type_size() == 0) return "";
        std::string text = " " + get_label(opt->get_type_name());
        if (!opt->get_default_str().empty()) text += "=" + opt->get_default_str();
        if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) text += " ...";
        if (opt->get_required()) text += " " + get_label("REQUIRED");
        return text;
    }
};

bool isTuningOption(std::string_view name) {
    for (const vkray::accel::TuningOption& o : vkray::accel::tuningOptions())
        if (o.name == name) return true;
    return false;
}

// CLI11's message for a wrong command line, as one line with where to look. Unexpected arguments
// are listed in the order given (CLI11 2.1's message reverses them).
std::string usageMessage(const CLI::App& app, const CLI::ParseError& e) {
    std::string message = e.what(), command = "vkray";
    const std::vector<CLI::App*> parsed = app.get_subcommands();
    for (const CLI::App* sub : parsed) command += " " + sub->get_name();
    const std::vector<std::string> extras = app.remaining(true);
    if (parsed.empty() && !extras.empty()) {  // not a subcommand: a typo, or no command at all
        std::vector<std::string> names;
        for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
        const std::optional<std::string> near = vkray::closestName(extras.front(), names);
        return "unknown command '" + extras.front() + "' (" + (near ? "did you mean '" + *near + "'?" : "see 'vkray --help'") + ")";
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && !extras.empty()) {
        std::string list, hint;
        for (const std::string& a : extras) {
            list += (list.empty() ? "" : " ") + a;
            if (hint.empty() && a.starts_with("--") && !parsed.empty()) {
                std::vector<std::string> flags;  // long names without their dashes
                for (const CLI::Option* o : parsed.back()->get_options())
                    for (const std::string& l : o->get_lnames()) flags.push_back(l);
                if (const auto near = vkray::closestName(a.substr(2), flags)) hint = "; did you mean --" + *near + "?";
                if (isTuningOption(a.substr(2)))
                    hint = "; tuning follows the accelerator's name: --accel NAME:" + a.substr(2) + "=VALUE";
            }
        }
        message = "unexpected argument" + std::string(extras.size() > 1 ? "s" : "") + ": " + list + hint;
    }
    return message + " (see '" + command + " --help')";
}

}  // namespace

int main(int argc, char** argv) {
    // Before any thread starts: it may set the Vulkan loader's environment (driver_filter.h).
    vkray::gpu::skipDriversWithoutDevices();
    CLI::App app{"vkray: a Vulkan compute ray tracer for studying acceleration structures"};
    app.set_version_flag("--version", VKRAY_VERSION);
    app.require_subcommand(1);
    app.formatter(std::make_shared<HelpFormatter>());  // before the subcommands, which copy it
    int exitCode = 0;
    vkray::cli::registerRenderCommand(app, exitCode);
    vkray::cli::registerDevicesCommand(app, exitCode);
    vkray::cli::registerCompareCommand(app, exitCode);
    vkray::cli::registerGenCommand(app, exitCode);
    vkray::cli::registerConvertCommand(app, exitCode);
    vkray::cli::registerAssembleCommand(app, exitCode);
    vkray::cli::registerBenchCommand(app, exitCode, argc, argv);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::fprintf(stderr, "error: %s\n", usageMessage(app, e).c_str());
        return kUsageExit;
    } catch (const vkray::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "error: out of host memory (an allocation failed past the estimate that --stats shows)\n");
        return 1;
    } catch (const vk::OutOfDeviceMemoryError& e) {
        std::fprintf(stderr, "error: out of device memory: %s\n", e.what());
        return 1;
    } catch (const vk::OutOfHostMemoryError& e) {
        std::fprintf(stderr, "error: out of host memory: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return exitCode;
}
