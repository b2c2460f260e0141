// A screenshot of an rbsim page (run.html, or rbsim poses --format html) in Debian's headless
// Chromium, for the docs. playwright-core comes from tests/rbsim/node_modules (scripts/install_deps.sh).
//   node scripts/screenshot_page.mjs RUN.html OUT.png ['t=1.5&trails=1' [WIDTHxHEIGHT]]
import { createRequire } from 'node:module';
import { resolve } from 'node:path';

const require = createRequire(resolve('tests/rbsim/package.json'));
const { chromium } = require('playwright-core');
const [page_file, out, query = '', size = '1280x720'] = process.argv.slice(2);
if (!page_file || !out) {
  console.error('usage: node scripts/screenshot_page.mjs RUN.html OUT.png [QUERY [WIDTHxHEIGHT]]');
  process.exit(2);
}
const [width, height] = size.split('x').map(Number);
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--disable-background-networking', '--disable-component-update', '--disable-sync', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width, height } });
  await page.goto(`file://${resolve(page_file)}${query ? `?${query}` : ''}`);
  await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 3, null, { timeout: 60000 });
  await page.screenshot({ path: out });
  console.log(`wrote ${out}`);
} finally {
  await browser.close();
}
