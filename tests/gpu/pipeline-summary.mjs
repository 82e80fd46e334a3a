// Summarises a pipeline log written with LANTERN_PIPELINE_LOG (see gpu-context.ts): per test file, the
// pipelines it asked for, how many of them no earlier file had compiled, and the seconds spent; then
// the costliest compiles that only one test asked for. Usage: node tests/gpu/pipeline-summary.mjs <log>
import { readFileSync } from 'node:fs';

// The test device is acquired as the CLI's is (src/cli/dawn.ts), which appends its own tab-separated
// lines to the same file: only gpu-context.ts's JSON lines are read.
const lines = readFileSync(process.argv[2], 'utf8').trim().split('\n').filter((l) => l.startsWith('{')).map((l) => JSON.parse(l));
// gpu-context.ts logs each compute pipeline's first dispatch as kind 'used'.
const used = new Set(lines.filter((r) => r.kind === 'used').map((r) => r.key));
const rows = lines.filter((r) => r.kind !== 'used');
const seen = new Set();
const files = new Map();
const testsOf = new Map();
for (const r of rows) {
  const f = files.get(r.file) ?? { requests: 0, fresh: 0, ms: 0, freshMs: 0 };
  f.requests++;
  f.ms += r.ms;
  if (!seen.has(r.key)) { seen.add(r.key); f.fresh++; f.freshMs += r.ms; }
  files.set(r.file, f);
  const t = testsOf.get(r.key) ?? { label: r.label, tests: new Set(), ms: 0 };
  t.tests.add(`${r.file} > ${r.test}`);
  t.ms = Math.max(t.ms, r.ms);
  testsOf.set(r.key, t);
}
const s = (ms) => (ms / 1000).toFixed(1);
console.log('file'.padEnd(34), 'requests', 'new', 'new s', 'all s');
for (const [file, f] of [...files].sort((a, b) => b[1].freshMs - a[1].freshMs)) console.log(file.padEnd(34), String(f.requests).padStart(8), String(f.fresh).padStart(3), s(f.freshMs).padStart(5), s(f.ms).padStart(5));
const total = [...files.values()].reduce((a, f) => ({ requests: a.requests + f.requests, fresh: a.fresh + f.fresh, freshMs: a.freshMs + f.freshMs }), { requests: 0, fresh: 0, freshMs: 0 });
console.log(`total: ${total.requests} requests, ${total.fresh} distinct pipelines, ${s(total.freshMs)} s compiling them`);
console.log('\ncostliest pipelines asked for by one test only:');
for (const [key, t] of [...testsOf].filter(([, t]) => t.tests.size === 1).sort((a, b) => b[1].ms - a[1].ms).slice(0, 40)) console.log(s(t.ms).padStart(6), t.label, key, '<-', [...t.tests][0]);
// Dawn returns the pipeline it already made for the same descriptor: a key is used where any of its pipelines was dispatched.
const unused = new Map();
for (const r of rows) if (r.kind.startsWith('compute') && !used.has(r.key)) unused.set(r.key, { ...r, ms: Math.max(r.ms, unused.get(r.key)?.ms ?? 0) });
if (used.size > 0) {
  console.log(`\ncompute pipelines compiled and never dispatched: ${unused.size} (${s([...unused.values()].reduce((a, r) => a + r.ms, 0))} s)`);
  for (const r of [...unused.values()].sort((a, b) => b.ms - a.ms)) console.log(s(r.ms).padStart(6), r.label, r.key, '<-', `${r.file} > ${r.test}`);
}
