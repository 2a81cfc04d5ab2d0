# Checks a merged bench report against its shards and against an unsharded run of the same
# settings. Input (jq -s): the merged bench.json, the unsharded one, then every shard's.
# Output: one line per mismatch; nothing when the merge is right.
def nopareto: del(.pareto);
def points($sc; f): [$sc.error_vs_time[] | select(f) | nopareto];
# The figures of one configuration in one scene's report (images are named per report: left out;
# so are an accelerator's primary_vs_bvh, a figure of two configurations that a shard holding only
# one of them cannot give, and its primary_vs_intersect1, whose divisor is the scene's Embree
# figure over every shard: checked on its own below).
def figures($sc; $name):
  if $name == "reference" then
    {reference: ($sc.reference | del(.images)), points: points($sc; .group == "cpu-reference")}
  elif ($name | startswith("accel ")) then ($name[6:]) as $a |
    {accel: [$sc.accelerators[] | select(.accel == $a)
             | del(.images, .primary_vs_bvh, .embree_interleaved.primary_vs_intersect1)],
     points: points($sc; .group == "accelerator" and .label == $a)}
  elif ($name | startswith("concurrent ")) then {concurrent: $sc.concurrent_build}
  elif ($name | startswith("aac-delta ")) then ($name[10:] | tonumber) as $d |
    {delta: [$sc.aac_delta_sweep[] | select(.aac_delta == $d)],
     points: points($sc; .group == "aac-delta" and .aac_delta == $d)}
  elif $name == "maxdepth-sweep" then {points: points($sc; .group == "maxdepth")}
  else {unknown: $name} end;
# What a report lists: per scene, its configurations and the rows and points they give.
def listing: [.scenes[] | {index, configurations: [.configurations[].label],
                            accelerators: [.accelerators[].accel], deltas: [.aac_delta_sweep[].aac_delta],
                            points: [.error_vs_time[].label], concurrent: (.concurrent_build != null)}];
.[0] as $m | .[1] as $u | .[2:] as $shards |
(if ($m | listing) != ($u | listing) then
   "the merged report lists \($m | listing | tojson), the unsharded run \($u | listing | tojson)" else empty end),
(if ($m.configurations.count != $u.configurations.count) or ($m.configurations.hash != $u.configurations.hash) then
   "configuration count/hash differ: merged \($m.configurations), unsharded \($u.configurations)" else empty end),
($m.scenes[] as $sc | $sc.configurations[] as $c |
  [$shards[] | select(.shard.index == $c.shard) | .scenes[] | select(.index == $sc.index)] as $src |
  if ($src | length) != 1 then "\($sc.name): \($c.label): \($src | length) shard reports hold it, expected 1"
  elif ($src[0].configurations | map(.label) | index($c.label)) == null then
    "\($sc.name): \($c.label): shard \($c.shard) did not measure it"
  elif figures($sc; $c.label) != figures($src[0]; $c.label) then
    "\($sc.name): \($c.label): merged figures differ from shard \($c.shard)'s"
  elif ($c.label | startswith("accel ")) and (figures($sc; $c.label).accel | length) != 1 then
    "\($sc.name): \($c.label): not one row in the merged report"
  else empty end),
# Every ratio to Embree divides by the scene's one Embree figure, the median of every shard's runs.
($m.scenes[] as $sc | select($sc.embree.version != null) | $sc.accelerators[] |
  select(.embree_interleaved != null) |
  ($sc.embree.intersect1_ms.median / .primary_only_ms.median) as $want |
  if ((.embree_interleaved.primary_vs_intersect1 - $want) | fabs) > 1e-9 * $want then
    "\($sc.name): \(.accel): primary_vs_intersect1 \(.embree_interleaved.primary_vs_intersect1), expected \($want)"
  else empty end)
