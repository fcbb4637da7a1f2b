// SPDX-License-Identifier: GPL-3.0-or-later
// What the browser scripts share: roifem serve started on a free loopback port, and Debian's
// headless Chromium with SwiftShader WebGL at 1200 x 800 (page_test.mjs, render_rate.mjs).
import { spawn } from 'node:child_process';
import puppeteer from 'puppeteer-core';

export const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Starts `roifem serve SCENARIO --port 0 ARGS...` and waits up to `seconds` for its "open http://..."
// line. Returns { server, url, log() (its output so far), exited (a promise of { code, signal }) }.
// Whatever fails later, the server is killed when node exits.
export async function startServe(roifem, scenario, args, seconds) {
  const server = spawn(roifem, ['serve', scenario, '--port', '0', ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  server.stdout.on('data', (d) => { output += d; });
  server.stderr.on('data', (d) => { output += d; });
  const exited = new Promise((resolve) => server.on('exit', (code, signal) => resolve({ code, signal })));
  process.on('exit', () => server.kill('SIGKILL'));
  let url = null;
  for (let k = 0; k < 10 * seconds && !url; ++k) {
    const m = output.match(/open (http:\/\/127\.0\.0\.1:[0-9]+\/)/);
    if (m) url = m[1];
    else await sleep(100);
  }
  if (!url) { console.log(output); throw new Error(`the server did not start within ${seconds} s`); }
  return { server, url, log: () => output, exited };
}

export function launchChromium() {
  return puppeteer.launch({
    executablePath: '/usr/bin/chromium', headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic', '--window-size=1200,800'],
  });
}
