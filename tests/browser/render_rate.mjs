// SPDX-License-Identifier: GPL-3.0-or-later
// How fast the page can draw the brain when nothing else runs (the physics idle, no grab): a measure
// of the renderer alone, beside page_test.mjs's frame rate while dragging (docs/simulator.md).
//   node render_rate.mjs ROIFEM SCENARIO [-- SERVE_OPTIONS...]
// Starts roifem serve, opens the page in Debian's headless Chromium (SwiftShader WebGL, 1200 x 800),
// asks for a redraw at every animation frame for 4 s and prints the frames drawn per second.
import { spawn } from 'node:child_process';
import puppeteer from 'puppeteer-core';

const [roifem, scenario, ...rest] = process.argv.slice(2);
if (!scenario) throw new Error('usage: node render_rate.mjs ROIFEM SCENARIO [-- SERVE_OPTIONS...]');
const serveOptions = rest[0] === '--' ? rest.slice(1) : [];
const server = spawn(roifem, ['serve', scenario, '--port', '0', ...serveOptions], { stdio: ['ignore', 'pipe', 'pipe'] });
let log = '';
server.stdout.on('data', (d) => { log += d; });
server.stderr.on('data', (d) => { log += d; });
process.on('exit', () => server.kill('SIGKILL'));
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
let url = null;
for (let k = 0; k < 3000 && !url; ++k) {  // a large brain's models take minutes to prepare
  const m = log.match(/open (http:\/\/127\.0\.0\.1:[0-9]+\/)/);
  if (m) url = m[1];
  else await sleep(100);
}
if (!url) { console.log(log); throw new Error('the server did not start within 300 s'); }
const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1200,800'],
});
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1200, height: 800 });
  await page.goto(url);
  await page.waitForFunction(() => window.roifem && window.roifem.ready && window.roifem.frames > 3, { timeout: 60000 });
  await sleep(1000);
  const measured = await page.evaluate(async () => {
    const before = window.roifem.framesDrawn, start = performance.now();
    while (performance.now() - start < 4000) {
      window.dispatchEvent(new Event('resize'));  // the view is drawn again at the next frame
      await new Promise((resolve) => requestAnimationFrame(resolve));
    }
    return { frames_per_s: (window.roifem.framesDrawn - before) / ((performance.now() - start) / 1000),
             surface_nodes: window.roifem.hello.vertices };
  });
  console.log(`render rate: ${measured.frames_per_s.toFixed(1)} frames/s drawn (${measured.surface_nodes} surface nodes, ` +
              '1200 x 800, the physics idle)');
} finally {
  await browser.close();
  server.kill('SIGINT');
}
