// A lightmap test scene as OBJ with lightmap UVs (vt): a 4 x 4 floor at y = 0 and, on it, an open box
// (its +X face, top and +Z face), each quad a chart of its own in a 2 x 2 atlas with a 1/16 margin;
// material Kd 0.8 (the albedo of the bake and of the sun's direct light).
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';

export function writeLightmapScene(folder) {
  const v = [], vt = [], f = [];
  const quad = (corner, u, w, n, chart) => {
    const base = v.length;
    const [cx, cy] = [chart % 2, Math.floor(chart / 2)];
    for (let j = 0; j <= n; j++) {
      for (let i = 0; i <= n; i++) {
        v.push([0, 1, 2].map((k) => corner[k] + (u[k] * i) / n + (w[k] * j) / n));
        vt.push([0.5 * cx + 1 / 16 + (0.5 - 1 / 8) * (i / n), 0.5 * cy + 1 / 16 + (0.5 - 1 / 8) * (j / n)]);
      }
    }
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        const a = base + j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
        f.push([a, b, d], [a, d, c]);
      }
    }
  };
  quad([-2, 0, -2], [0, 0, 4], [4, 0, 0], 8, 0);
  quad([0.5, 0.001, -0.5], [0, 1, 0], [0, 0, 1], 4, 1);
  quad([-0.5, 1, -0.5], [0, 0, 1], [1, 0, 0], 4, 2);
  quad([-0.5, 0.001, 0.5], [1, 0, 0], [0, 1, 0], 4, 3);
  writeFileSync(join(folder, 'lightmap.mtl'), 'newmtl grey\nKd 0.8 0.8 0.8\n');
  const lines = ['mtllib lightmap.mtl', 'usemtl grey', ...v.map((p) => `v ${p.join(' ')}`), ...vt.map((t) => `vt ${t.join(' ')}`),
                 ...f.map((t) => `f ${t.map((i) => `${i}/${i}`).join(' ')}`)];
  writeFileSync(join(folder, 'lightmap.obj'), lines.join('\n') + '\n');
  return join(folder, 'lightmap.obj');
}
