// SPDX-License-Identifier: GPL-3.0-or-later
// docs/simulator-cut.png: the scalpel on setup 1's cut model (static-cut), as a person would use it:
// the view zoomed on the ROI, a stroke of the mouse beside where the hand then presses, and the
// hand pulling the tissue beside the cut open.
//   node tests/browser/cut_picture.mjs ROIFEM SCENARIO OUT.png [--pick-mm X,Y,Z]
import path from 'node:path';
import { startServe, launchChromium, sleep } from './serve_page.mjs';

const [roifem, scenario, out, ...rest] = process.argv.slice(2);
if (!out) throw new Error('usage: node cut_picture.mjs ROIFEM SCENARIO OUT.png [--pick-mm X,Y,Z]');
const pickMm = rest[0] === '--pick-mm' ? rest[1].split(',').map(Number) : [0, -20, 48];
const { server, url, log } = await startServe(roifem, scenario, ['--models', 'static-cut'], 60);
const browser = await launchChromium();
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1200, height: 800 });
  await page.goto(url);
  await page.waitForFunction(() => window.roifem && window.roifem.ready && window.roifem.frames > 3, { timeout: 30000 });
  let at = await page.evaluate((p) => window.roifem.screenOf(...p), pickMm);
  await page.mouse.move(at.x, at.y);
  for (let k = 0; k < 12; ++k) { await page.mouse.wheel({ deltaY: -120 }); await sleep(50); }
  at = await page.evaluate((p) => window.roifem.screenOf(...p), pickMm);
  await page.click('#scalpel');
  await page.$eval('#cut-depth', (e) => { e.value = '8'; });
  for (const dx of [-60]) {  // a stroke down the view beside the hand
    await page.mouse.move(at.x + dx, at.y + 15);
    await page.mouse.down();
    for (let k = 1; k <= 20; ++k) { await page.mouse.move(at.x + dx, at.y + 15 + 8 * k); await sleep(20); }
    await page.mouse.up();
    await sleep(500);
  }
  await page.click('#scalpel');
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  for (let k = 1; k <= 30; ++k) { await page.mouse.move(at.x + 2 * k, at.y - 1 * k); await sleep(20); }
  await sleep(400);
  await page.screenshot({ path: out });
  await page.mouse.up();
  console.log((await page.evaluate(() => window.roifem.notices)).join('\n'));
  console.log(`wrote ${path.resolve(out)}`);
} finally {
  await browser.close();
  server.kill('SIGINT');
}
if (!/removed from the static-cut model/.test(log())) { console.log(log()); process.exit(1); }
