// The Unity importer itself (probes/unity/PrtProbeImporter.cs), compiled with Debian's mono-mcs
// against stand-in UnityEngine / UnityEditor types (unity/UnityStubs.cs) and run on the fixture's
// exports by unity/RunImporter.cs (see there for what is checked and what stays re-implemented).
// Exit 77 (ctest: skipped) only when mcs or mono is missing (Debian package mono-mcs).
// Usage: node test_unity.mjs --work DIR (the engines_fixture output)
import { spawnSync } from 'node:child_process';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { argument, fixtureFolders, run } from './common.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const work = argument('work');
for (const tool of ['mcs', 'mono'])
  if (spawnSync('sh', ['-c', `command -v ${tool}`]).status !== 0) {
    console.log(`SKIP: ${tool} is not installed (Debian package mono-mcs)`);
    process.exit(77);
  }
const exe = join(work, 'run_importer.exe');
run('mcs', ['-nologo', '-warnaserror', '-nowarn:649', '-define:UNITY_EDITOR', `-out:${exe}`, resolve(here, '../../probes/unity/PrtProbeImporter.cs'),
            join(here, 'unity', 'UnityStubs.cs'), join(here, 'unity', 'RunImporter.cs')]);
const args = fixtureFolders(work).flatMap((f) => [join(f.dir, 'unity.json'), join(f.dir, 'truth.json')]);
const r = spawnSync('mono', [exe, ...args], { encoding: 'utf8' });
process.stdout.write(r.stdout + r.stderr);
process.exit(r.status === 0 ? 0 : 1);
