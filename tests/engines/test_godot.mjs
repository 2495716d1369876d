// The Godot importer (probes/godot/prt_probe_import.gd) as far as the tools here allow: no Godot runs
// on these machines, so the script is parsed with a Godot 4 GDScript grammar (npm tree-sitter-gdscript
// with the tree-sitter node binding): it must parse without ERROR or MISSING nodes, and the keys and
// format name it reads must be the ones prt's Godot export writes (format "prt-probes-godot", probes[i]
// "position", "valid", "sh" of 27 floats). Godot's evaluation of the sh (the lightmap capture shader)
// stays re-implemented in tests/probes/test_engine_exports.cpp.
// Usage: node test_godot.mjs --work DIR (the engines_fixture output) [--script FILE.gd]
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Checker, argument, fixtureFolders } from './common.mjs';

const require = createRequire(import.meta.url);
const Parser = require('tree-sitter');
const GDScript = require('tree-sitter-gdscript');
const here = dirname(fileURLToPath(import.meta.url));
const work = argument('work');
const script = argument('script', resolve(here, '../../probes/godot/prt_probe_import.gd'));
const check = new Checker('engines_godot');

const parser = new Parser();
parser.setLanguage(GDScript);
const tree = parser.parse(readFileSync(script, 'utf8'));
const problems = [], strings = new Set(), functions = new Set();
(function walk(node) {
  if (node.type === 'ERROR' || node.isMissing) problems.push(`${node.type} at line ${node.startPosition.row + 1}`);
  if (node.type === 'string') strings.add(node.text.slice(1, -1));
  if (node.type === 'function_definition') functions.add(node.childForFieldName('name').text);
  for (const child of node.children) walk(child);
})(tree.rootNode);
check.check(`${script} parses as GDScript`, problems.length === 0 && !tree.rootNode.hasError, problems.join(', '));
check.check(`${script} defines _run and apply_probes`, functions.has('_run') && functions.has('apply_probes'), [...functions].join(', '));
for (const key of ['format', 'prt-probes-godot', 'probes', 'position', 'valid', 'sh'])
  check.check(`${script} reads "${key}"`, strings.has(key));

for (const { name, dir } of fixtureFolders(work)) {
  const doc = JSON.parse(readFileSync(join(dir, 'godot.json'), 'utf8'));
  check.check(`${name}: godot.json format is the one the script accepts`, doc.format === 'prt-probes-godot');
  check.check(`${name}: every probe has position (3), valid and sh (27)`,
              doc.probes.every((p) => p.position.length === 3 && typeof p.valid === 'boolean' && p.sh.length === 27));
}
check.finish();
