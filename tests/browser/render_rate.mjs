// SPDX-License-Identifier: GPL-3.0-or-later
// How fast the page can draw the brain when nothing else runs (the physics idle, no grab): a measure
// of the renderer alone, beside page_test.mjs's frame rate while dragging (docs/simulator.md).
//   node render_rate.mjs ROIFEM SCENARIO [-- SERVE_OPTIONS...]
// Starts roifem serve, opens the page in Debian's headless Chromium (SwiftShader WebGL, 1200 x 800),
// asks for a redraw at every animation frame for 4 s and prints the frames drawn per second.
import { launchChromium, sleep, startServe } from './serve_page.mjs';

const [roifem, scenario, ...rest] = process.argv.slice(2);
if (!scenario) throw new Error('usage: node render_rate.mjs ROIFEM SCENARIO [-- SERVE_OPTIONS...]');
const serveOptions = rest[0] === '--' ? rest.slice(1) : [];
const { server, url } = await startServe(roifem, scenario, serveOptions, 300);  // a large brain's models take minutes
const browser = await launchChromium();
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
