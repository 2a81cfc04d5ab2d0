// The shard sections of a merged report (bench_merge.h): who measured what, as Markdown and HTML.
#include <string>
#include <vector>

#include "bench/bench_merge.h"
#include "bench/bench_shard.h"
#include "bench/report_tables.h"
#include "bench/svg_plot.h"

namespace vkray::bench {
namespace {

struct Rows {
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;
};

const ShardInfo* shardOf(const BenchResults& r, int index) {
    for (const ShardInfo& s : r.shards)
        if (s.shard.index == index) return &s;
    return nullptr;
}

Rows shardRows(const BenchResults& r) {
    Rows t{{"shard", "node", "device", "driver", "hardware threads", "started (UTC)", "took s", "configurations"}, {}};
    for (const ShardInfo& s : r.shards)
        t.rows.push_back({shardText(s.shard), s.node, s.device, s.driver, std::to_string(s.hardwareThreads),
                          s.startedAt, formatNumber(s.elapsedSeconds), std::to_string(s.configurations)});
    return t;
}

Rows configurationRows(const BenchResults& r) {
    Rows t{{"scene", "configuration", "shard", "node", "device"}, {}};
    for (const SceneResult& scene : r.scenes)
        for (const ConfigurationRun& c : scene.configurations) {
            const ShardInfo* s = shardOf(r, c.shard);
            t.rows.push_back({scene.name, c.label, std::to_string(c.shard), s ? s->node : kMissing,
                              s ? s->device : kMissing});
        }
    return t;
}

std::string intro(const BenchResults& r) {
    return "This report merges the " + std::to_string(r.shards.size()) + " shards of one run (`vkray bench --shard I/" +
           std::to_string(r.shards.size()) + "`): " + std::to_string(r.configurationCount) +
           " configurations, each with the figures of the shard that measured it; the Pareto front is marked over "
           "all of them, and each scene's Embree figures summarise every shard's Embree timings.";
}

std::string markdownCell(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '|') out += "\\|";
        else if (c == '\n' || c == '\r') out += ' ';
        else out += c;
    }
    return out;
}

std::string markdownTable(const Rows& t) {
    std::string out = "|";
    for (const std::string& c : t.columns) out.append(" ").append(c).append(" |");
    out += "\n|";
    for (size_t i = 0; i < t.columns.size(); ++i) out += " :--- |";
    out += "\n";
    for (const auto& row : t.rows) {
        out += "|";
        for (const std::string& c : row) out.append(" ").append(markdownCell(c)).append(" |");
        out += "\n";
    }
    return out + "\n";
}

std::string htmlTable(const Rows& t) {
    std::string out = "<div class=\"scroll\"><table>\n<thead><tr>";
    for (const std::string& c : t.columns) out += "<th>" + escapeXml(c) + "</th>";
    out += "</tr></thead>\n<tbody>\n";
    for (const auto& row : t.rows) {
        out += "<tr>";
        for (const std::string& c : row) out += "<td>" + escapeXml(c) + "</td>";
        out += "</tr>\n";
    }
    return out + "</tbody>\n</table></div>\n";
}

}  // namespace

std::string shardsMarkdown(const BenchResults& r) {
    if (r.shards.empty()) return "";
    return "## Shards\n\n" + intro(r) + "\n\n" + markdownTable(shardRows(r)) + "### Who measured what\n\n" +
           markdownTable(configurationRows(r));
}

std::string shardsHtml(const BenchResults& r) {
    if (r.shards.empty()) return "";
    std::string intro_ = intro(r);
    return "<section id=\"shards\">\n<h2>Shards</h2>\n<p>" + escapeXml(intro_) + "</p>\n" + htmlTable(shardRows(r)) +
           "<h3>Who measured what</h3>\n" + htmlTable(configurationRows(r)) + "</section>\n";
}

}  // namespace vkray::bench
