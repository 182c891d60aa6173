// triage_click.mjs — a person's triage in the report page, by clicking: opens a conform run's
// report/index.html from file:// in headless Chromium, ticks "known failure" on each named case and
// types its bug link, clicks "download expectations.txt" and waits for the file (report_triage_test.py).
//
//   node triage_click.mjs --page INDEX_HTML --download DIR --web ENGINES_WEB_DIR [--chromium EXE] \
//        --mark scene@technique=BUG_LINK [--mark ...]
// Prints the page's count line ("2 of 2 marked"); exits 1 with one line on any failure.
import path from 'node:path';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';

function parse(argv) {
  const a = { mark: [] };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (!['page', 'download', 'web', 'chromium', 'mark'].includes(key) || i + 1 >= argv.length) throw new Error(`bad argument ${argv[i]}`);
    if (key === 'mark') a.mark.push(argv[i + 1]); else a[key] = argv[i + 1];
  }
  for (const k of ['page', 'download', 'web']) if (!a[k]) throw new Error(`--${k} is required`);
  return a;
}

async function main() {
  const a = parse(process.argv.slice(2));
  // puppeteer-core as the web harnesses pin it (engines/web/package-lock.json).
  const puppeteer = createRequire(path.join(path.resolve(a.web), 'package.json'))('puppeteer-core');
  fs.mkdirSync(a.download, { recursive: true });
  const browser = await puppeteer.launch({
    executablePath: a.chromium || '/usr/bin/chromium',
    headless: true,
    // A test machine runs this as root, where Chromium's sandbox cannot start; nothing is fetched.
    args: ['--no-sandbox', '--host-resolver-rules=MAP * ~NOTFOUND', '--disable-background-networking', '--no-first-run',
      '--disable-extensions'],
  });
  try {
    const session = await browser.target().createCDPSession();
    const done = new Promise((resolve, reject) => {
      session.on('Browser.downloadProgress', (e) => {
        if (e.state === 'completed') resolve();
        if (e.state === 'canceled') reject(new Error('the download was cancelled'));
      });
    });
    await session.send('Browser.setDownloadBehavior', { behavior: 'allow', downloadPath: path.resolve(a.download), eventsEnabled: true });
    const page = await browser.newPage();
    await page.goto(pathToFileURL(path.resolve(a.page)).href, { waitUntil: 'load' });
    for (const m of a.mark) {
      const [name, bug] = [m.slice(0, m.indexOf('=')), m.slice(m.indexOf('=') + 1)];
      const row = `.triage[data-case="${name}"]`;
      if (!(await page.$(row))) throw new Error(`no triage marks for ${name} in ${a.page}`);
      await page.click(`${row} .triage-known`);
      await page.type(`${row} .triage-bug`, bug);
    }
    await page.click('#triage-download');
    await Promise.race([done, new Promise((_, reject) => setTimeout(() => reject(new Error('no download within 20 s')), 20000))]);
    process.stdout.write((await page.$eval('#triage-count', (e) => e.textContent)) + '\n');
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  process.stderr.write(`triage_click.mjs: ${e.message}\n`);
  process.exit(1);
});
