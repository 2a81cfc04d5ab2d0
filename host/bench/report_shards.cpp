// The shard sections of a merged report (bench_merge.h): who measured what, as Markdown and HTML.
#include <string>
#include <vector>

#include "bench/bench_merge.h"
#include "bench/bench_shard.h"
#include "bench/report_tables.h"
#include "bench/svg_plot.h"

namespace vkray::bench {
namespace {

const ShardInfo* shardOf(const BenchResults& r, int index) {
    for (const ShardInfo& s : r.shards)
        if (s.shard.index == index) return &s;
    return nullptr;
}

Table shardTable(const BenchResults& r) {
    Table t;
    t.title = "Where each shard ran";
    t.columns = {"shard", "node", "device", "driver", "hardware threads", "started (UTC)", "took s", "configurations"};
    t.numeric = {false, false, false, false, true, false, true, true};
    for (const ShardInfo& s : r.shards)
        t.rows.push_back({shardText(s.shard), s.node, s.device, s.driver, std::to_string(s.hardwareThreads),
                          s.startedAt, formatNumber(s.elapsedSeconds), std::to_string(s.configurations)});
    return t;
}

Table configurationTable(const BenchResults& r) {
    Table t;
    t.title = "Who measured what";
    t.columns = {"scene", "configuration", "shard", "node", "device"};
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

}  // namespace

std::string shardsMarkdown(const BenchResults& r) {
    if (r.shards.empty()) return "";
    return "## Shards\n\n" + intro(r) + "\n\n" + markdownTable(shardTable(r)) + markdownTable(configurationTable(r));
}

std::string shardsHtml(const BenchResults& r) {
    if (r.shards.empty()) return "";
    return "<section id=\"shards\">\n<h2>Shards</h2>\n<p>" + escapeXml(intro(r)) + "</p>\n" + htmlTable(shardTable(r)) +
           htmlTable(configurationTable(r)) + "</section>\n";
}

}  // namespace vkray::bench
