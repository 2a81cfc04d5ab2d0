// bench.md: the run with its warnings, the summary across scenes, then per scene the verdict and the
// tables of report_tables.h as GitHub Markdown (pipe tables), ready to paste into docs/performance.md.
#include <optional>
#include <string>

#include "bench/bench_resume.h"
#include "bench/report.h"
#include "bench/report_tables.h"

namespace vkray::bench {
namespace {

// A cell must stay on one line and must not end its column early.
std::string cell(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '|') out += "\\|";
        else if (c == '\n' || c == '\r') out += ' ';
        else out += c;
    }
    return out;
}

std::string factList(const Facts& facts) {
    std::string out;
    for (const auto& [label, value] : facts) out += "- **" + label + ":** " + cell(value) + "\n";
    return out + "\n";
}

std::string tableRow(const std::vector<std::string>& cells) {
    std::string out = "|";
    for (const std::string& c : cells) out.append(" ").append(cell(c)).append(" |");
    return out + "\n";
}


std::string sceneSection(const SceneResult& scene) {
    std::string out = "## " + scene.name + "\n\n" + factList(sceneFacts(scene));
    out += "**Who wins:** " + whoWins(scene) + "\n\n";
    for (const Table& t : sceneTables(scene)) out += markdownTable(t);
    return out;
}

}  // namespace

std::string markdownTable(const Table& t) {
    std::string out = "### " + t.title + "\n\n";
    if (t.rows.empty()) return out + t.whenEmpty + "\n\n";
    out += tableRow(t.columns);
    out += "|";
    for (size_t i = 0; i < t.columns.size(); ++i) out += i < t.numeric.size() && t.numeric[i] ? " ---: |" : " :--- |";
    out += "\n";
    for (const auto& row : t.rows) out += tableRow(row);
    out += "\n";
    for (const std::string& note : t.notes) out += note + "\n\n";
    return out;
}

std::string benchMarkdown(const BenchResults& results) {
    // A merged report lists its shards right after the run's facts.
    std::string out = "# vkray bench\n\n";
    if (!results.complete()) out += "> **Incomplete:** " + cell(incompleteNotice(results)) + "\n\n";
    out += factList(runFacts(results));
    for (const std::string& w : runWarnings(results)) out += "> **Warning:** " + cell(w) + "\n\n";
    out += shardsMarkdown(results);
    if (const std::optional<Table> summary = summaryTable(results)) out += "## Summary\n\n" + markdownTable(*summary);
    if (results.scenes.empty()) out += "No scene was run.\n";
    for (const SceneResult& scene : results.scenes) out += sceneSection(scene);
    return out;
}

}  // namespace vkray::bench
