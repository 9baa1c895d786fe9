#include "regress/report_style.h"

namespace vesper::regress {

std::string_view report_css() {
  return R"css(
:root { --pass: #1a7f37; --regressed: #c62828; --error: #a04a00; --ink: #1b1d21;
  --muted: #555b66; --rule: #d5d8de; --panel: #f5f6f8; }
* { box-sizing: border-box; }
body { margin: 0; font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif;
  color: var(--ink); background: #fff; }
header, main, footer { max-width: 1400px; margin: 0 auto; padding: 0 20px; }
header { padding-top: 18px; border-bottom: 1px solid var(--rule); }
h1 { font-size: 1.4rem; margin: 0 0 6px; }
h2 { font-size: 1.25rem; margin: 0 0 10px; }
h3 { font-size: 1.05rem; margin: 18px 0 8px; }
code { font: 0.9em ui-monospace, "DejaVu Sans Mono", monospace; word-break: break-all; }
a { color: #0b57a4; }
.overall { display: inline-block; font-size: 2rem; font-weight: 700; margin: 6px 0 10px;
  padding: 6px 18px; border-radius: 8px; color: #fff; }
.overall.v-pass { background: var(--pass); } .overall.v-regressed { background: var(--regressed); }
.overall.v-error { background: var(--error); }
.verdict { display: inline-block; font-weight: 700; font-size: 0.85rem; padding: 1px 8px;
  border-radius: 4px; color: #fff; letter-spacing: 0.03em; white-space: nowrap; }
.verdict.v-pass { background: var(--pass); } .verdict.v-regressed { background: var(--regressed); }
.verdict.v-error { background: var(--error); }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px; margin: 8px 0 16px; }
dl.facts dt { color: var(--muted); } dl.facts dd { margin: 0; }
table { border-collapse: collapse; margin: 8px 0 16px; }
caption { text-align: left; font-weight: 600; padding: 4px 0; }
th, td { border-bottom: 1px solid var(--rule); padding: 5px 10px; text-align: left; vertical-align: top; }
th { background: var(--panel); font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td ul, .reasons { margin: 0; padding-left: 18px; }
section.scene { border-top: 3px solid var(--rule); padding: 18px 0 8px; }
section.scene.v-regressed { border-top-color: var(--regressed); }
section.scene.v-error { border-top-color: var(--error); }
section.layer { background: var(--panel); border-radius: 8px; padding: 10px 14px 4px; margin: 12px 0; }
.error-box { border: 2px solid var(--error); background: #fff4e5; border-radius: 8px;
  padding: 10px 14px; margin: 8px 0 12px; font-size: 1.05rem; }
.error-box ul { margin: 4px 0 0; padding-left: 20px; }
.power { font-size: 1.05rem; } .note { color: var(--muted); }
.pictures { display: grid; grid-template-columns: repeat(auto-fill, minmax(240px, 1fr)); gap: 12px; }
figure { margin: 0; } figcaption { font-size: 0.85rem; color: var(--muted); margin-top: 4px; }
.frame { position: relative; line-height: 0; background: #000; }
.frame img { width: 100%; height: auto; image-rendering: pixelated; display: block; }
.frame svg { position: absolute; inset: 0; width: 100%; height: 100%; }
.missing { border: 1px dashed var(--muted); padding: 24px 10px; text-align: center; color: var(--muted); }
.region-outer { fill: none; stroke: #000; stroke-width: 4; vector-effect: non-scaling-stroke; }
.region-inner { fill: none; stroke: #ffd400; stroke-width: 2; vector-effect: non-scaling-stroke; }
.region-label { fill: #ffd400; stroke: #000; stroke-width: 0.6px; paint-order: stroke; font-weight: 700; }
.charts { display: flex; flex-wrap: wrap; gap: 10px; }
svg.chart { max-width: 100%; height: auto; background: #fff; border: 1px solid var(--rule); border-radius: 6px; }
svg.legend-bar { display: block; margin-top: 4px; max-width: 100%; }
svg.chart text, svg.legend-bar text { font: 11px system-ui, sans-serif; fill: var(--ink); }
.region-label { font-family: system-ui, sans-serif; }
svg .chart-title { font-size: 13px; font-weight: 600; }
svg .axis-title { font-size: 11px; fill: var(--muted); }
svg .plot-area { fill: #fafbfc; } svg .grid { stroke: #e3e6ea; } svg .axis { stroke: #8a909a; }
svg .line { fill: none; stroke: #0b57a4; stroke-width: 2; }
svg .reference { stroke: #555b66; stroke-width: 1.5; stroke-dasharray: 5 4; }
svg .m-pass { fill: var(--pass); stroke: #fff; } svg .m-regressed { fill: var(--regressed); stroke: #fff; }
svg .m-error { fill: var(--error); stroke: #fff; }
svg .h-golden { fill: #c9cdd4; stroke: #8a909a; stroke-width: 1; }
svg .h-new { fill: none; stroke: #0b57a4; stroke-width: 2; }
svg .median-golden { stroke: #555b66; stroke-width: 1.5; stroke-dasharray: 4 3; }
svg .median-new { stroke: #0b57a4; stroke-width: 1.5; }
footer { color: var(--muted); font-size: 0.85rem; padding: 20px; }
.visually-hidden { position: absolute; width: 1px; height: 1px; overflow: hidden; clip: rect(0 0 0 0); }
)css";
}

}  // namespace vesper::regress
