// Bundles viewer.js and the parts of three.js it uses into one classic script (no imports), safe
// inside an HTML <script> element: viewer.bundle.js, committed, which rbsim links in and inlines
// into run.html. `node build.mjs --check` rebuilds into memory and fails when the committed file
// differs (CI runs it: the bundle is what the sources and the pinned packages make).
//   cd apps/rbsim/viewer && npm ci && node build.mjs [--check]
import { build } from 'esbuild';
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const result = await build({
  entryPoints: [join(here, 'viewer.js')],
  bundle: true,
  format: 'iife',
  minify: true,
  target: 'es2020',
  legalComments: 'eof',
  write: false,
  logLevel: 'error',
});
// "</script" would end the element early, and "<!--" would start an escape state in it.
const text = result.outputFiles[0].text.replace(/<\/(script)/gi, '<\\/$1').replace(/<!--/g, '<\\!--');
const out = join(here, 'viewer.bundle.js');
if (process.argv.includes('--check')) {
  if (readFileSync(out, 'utf8') !== text) {
    console.error(`${out} is not what build.mjs makes of viewer.js and the pinned packages: run node build.mjs`);
    process.exit(1);
  }
  console.log('viewer.bundle.js is current');
} else {
  writeFileSync(out, text);
  console.log(`wrote ${out} (${text.length} bytes)`);
}
