// Bundles the viewer (src/main.js with three.js, by esbuild) and the trajectory files given into
// one self-contained HTML page: browsers block ES modules and fetch() on file:// pages, so the
// script and the data are inlined.
//   node build.mjs OUT.html TRAJECTORY.json...
import { build } from 'esbuild';
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const [out, ...inputs] = process.argv.slice(2);
if (!out || inputs.length === 0) {
  console.error('usage: node build.mjs OUT.html TRAJECTORY.json...');
  process.exit(2);
}
const trajectories = inputs.map((file) => {
  let data;
  try {
    data = JSON.parse(readFileSync(file, 'utf8'));
  } catch (e) {
    console.error(`${file}: not a trajectory file (${e.message.split('\n')[0]})`);
    process.exit(2);
  }
  if (data.schema !== 1 || !Array.isArray(data.steps) || !Array.isArray(data.geoms)) {
    console.error(`${file}: not a trajectory file (schema 1 with steps and geoms expected)`);
    process.exit(2);
  }
  data.file = basename(file);
  return data;
});
const bundle = await build({
  entryPoints: [join(here, 'src/main.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  write: false,
  logLevel: 'error',
});
// Inside <script>, "</script" would end the element: escape every "</".
const inline = (text) => text.replace(/<\//g, '<\\/');
const html = readFileSync(join(here, 'index.html'), 'utf8')
  .replace('/*TRAJECTORIES*/', () => inline(JSON.stringify(trajectories)))
  .replace('/*BUNDLE*/', () => inline(bundle.outputFiles[0].text));
mkdirSync(dirname(out), { recursive: true });
writeFileSync(out, html);
console.error(`wrote ${out} (${(html.length / 1e6).toFixed(1)} MB, ${trajectories.length} grasps)`);
