// The viewer end to end in a real browser (issue 23, spec §20): Debian's
// chromium, headless, driven by playwright-core. It starts `sombra view`,
// opens the URL it prints, and checks what a user sees:
//   1. after the passes end, the page's image equals `sombra render` of the
//      same scene at the same spp, up to 8-bit rounding (±1 per channel);
//   2. a second tab sees the same render, and follows the camera the first moves;
//   3. a drag orbits the camera: the image changes and refines again;
//   4. a click on a pixel shows explain's story in the side panel, with the
//      pixel's value equal to what `sombra explain --json` gives for it at
//      that camera;
//   5. the denoise switch (spec §25): on, the page ends on the last pass
//      denoised, `sombra render --denoise` up to 8-bit rounding; off, the
//      raw image again;
//   6. a glTF file's orthographic camera stays orthographic: `+` zooms by
//      its half-height, the origin stays, and the image grows;
//   7. a signal ends the server at once and frees the port (SIGTERM: a
//      process that a non-interactive shell starts in the background inherits
//      SIGINT ignored, as CI's may; Ctrl-C itself is tested by interrupt_test).
// Screenshots go to $SOMBRA_ARTIFACTS (CI keeps them).
//
//   SOMBRA_EXE=build/release/src/app/sombra node tools/browser/viewer_e2e.mjs
//
// Exit 0: passed; 1: failed; 77: skipped (no chromium or no playwright-core;
// a failure instead when SOMBRA_REQUIRE_BROWSER is set, as in CI).
import { spawn, spawnSync } from "node:child_process";
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, "../..");
const exe = process.env.SOMBRA_EXE ?? path.join(repo, "build/release/src/app/sombra");
const artifacts = process.env.SOMBRA_ARTIFACTS ?? path.join(repo, "build/release/viewer-e2e");
const chromiumPaths = ["/usr/lib/chromium/chromium", "/usr/bin/chromium"];
const WIDTH = 96, HEIGHT = 72, SPP = 8;

function skip(why) {
  if (process.env.SOMBRA_REQUIRE_BROWSER) fail(`${why} (SOMBRA_REQUIRE_BROWSER is set: tools/install-deps.sh installs it)`);
  console.log(`SKIPPED: ${why}`);
  process.exit(77);
}
function fail(why) {
  console.error(`FAILED: ${why}`);
  process.exitCode = 1;
  throw new Error(why);
}
function check(condition, what) {
  if (!condition) fail(what);
  console.log(`ok: ${what}`);
}

let chromium;
try {
  ({ chromium } = await import("playwright-core"));
} catch {
  skip("playwright-core is not installed in tools/browser/node_modules");
}
const browserPath = chromiumPaths.find((p) => existsSync(p));
if (!browserPath) skip("Debian's chromium is not installed");
if (!existsSync(exe)) skip(`no sombra executable at ${exe} (set SOMBRA_EXE)`);
mkdirSync(artifacts, { recursive: true });

// A small scene of the repository's: the Cornell box under the direct
// integrator (fast, and every pixel deterministic for a given spp).
const work = mkdtempSync(path.join(tmpdir(), "sombra-viewer-e2e-"));
const scene = path.join(repo, "scenes/cornell-box.json");
const common = ["--width", String(WIDTH), "--height", String(HEIGHT), "--spp", String(SPP), "--threads", "2"];

function runSombra(args) {
  const r = spawnSync(exe, args, { encoding: "utf8", timeout: 60000 });
  if (r.status !== 0) fail(`sombra ${args.join(" ")}: exit ${r.status}: ${r.stderr}`);
  return r.stdout;
}

// A server for `file`, and its URL: the first line on standard output.
async function serve(file) {
  const child = spawn(exe, ["view", file, ...common, "--port", "0", "--quiet"], { stdio: ["ignore", "pipe", "pipe"] });
  let err = "";
  child.stderr.on("data", (d) => { err += d; });
  const address = await new Promise((resolve, reject) => {
    let out = "";
    const timer = setTimeout(() => reject(new Error("sombra view printed no URL within 30 s: " + err)), 30000);
    child.stdout.on("data", (d) => {
      out += d;
      const line = out.split("\n").find((l) => l.startsWith("http://127.0.0.1:"));
      if (line) { clearTimeout(timer); resolve(line.trim()); }
    });
    child.on("exit", (code) => reject(new Error(`sombra view exited (${code}): ${err}`)));
  });
  return { child, address };
}
const { child: server, address: url } = await serve(scene);
const port = Number(new URL(url).port);
console.log(`serving at ${url}`);

const browser = await chromium.launch({
  executablePath: browserPath,
  headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-zygote"],
});
let passed = false;
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
  page.on("pageerror", (e) => fail(`the page threw: ${e.message}`));
  await page.goto(url);

  // The status line reads "pass N · S / T spp · … · done" once the passes end.
  const waitDone = async (p, after = "") =>
    p.waitForFunction((prev) => {
      const t = document.getElementById("status").textContent;
      return t.includes("done") && t !== prev;
    }, after, { timeout: 60000 });
  await waitDone(page);
  // The image the page shows, or the image at URL `src` decoded by the same
  // page, as RGBA bytes (read back through a canvas).
  const pixelsOf = (p, src = null) =>
    p.evaluate(async (url) => {
      const img = url ? new Image() : document.getElementById("view");
      if (url) img.src = url;
      else if (!img.complete) await new Promise((r) => img.addEventListener("load", r, { once: true }));
      await img.decode();
      const c = document.createElement("canvas");
      c.width = img.naturalWidth; c.height = img.naturalHeight;
      const g = c.getContext("2d");
      g.drawImage(img, 0, 0);
      return { width: c.width, height: c.height, data: Array.from(g.getImageData(0, 0, c.width, c.height).data) };
    }, src);
  // Wait for the image of the last pass to be the one shown.
  await page.waitForFunction(() => {
    const img = document.getElementById("view");
    return img.complete && img.naturalWidth > 0;
  });
  await page.waitForTimeout(300);
  const shown = await pixelsOf(page);
  await page.screenshot({ path: path.join(artifacts, "1-refined.png") });

  // 1. The same image as `sombra render`, decoded by the same browser.
  const reference = path.join(work, "reference.png");
  runSombra(["render", scene, ...common, "-o", reference, "--quiet"]);
  const refPixels = await pixelsOf(page, "data:image/png;base64," + readFileSync(reference).toString("base64"));
  check(shown.width === WIDTH && shown.height === HEIGHT, `the page shows a ${WIDTH}×${HEIGHT} image`);
  let worst = 0;
  for (let i = 0; i < shown.data.length; ++i) worst = Math.max(worst, Math.abs(shown.data[i] - refPixels.data[i]));
  check(worst <= 1, `the refined image equals sombra render at ${SPP} spp up to 8-bit rounding (largest difference ${worst})`);

  // 2. A second tab sees the same render.
  const second = await browser.newPage({ viewport: { width: 1100, height: 700 } });
  await second.goto(url);
  await waitDone(second);
  await second.waitForFunction(() => document.getElementById("view").naturalWidth > 0);
  await second.waitForTimeout(300);
  const secondShown = await pixelsOf(second);
  check(secondShown.data.every((v, i) => v === shown.data[i]), "a second tab shows the same image");

  // 3. A drag orbits: the image changes, and the passes start again and end.
  const box = await page.locator("#view").boundingBox();
  const statusBefore = await page.locator("#status").textContent();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let k = 1; k <= 8; ++k) await page.mouse.move(box.x + box.width / 2 + 6 * k, box.y + box.height / 2 + k);
  await page.mouse.up();
  // The page sends one camera at a time and the latest after it: wait until
  // the last has been sent, so that the camera below is the final one.
  await page.waitForFunction(() => !sending && !queued, null, { timeout: 20000 });
  await page.waitForFunction(() => !document.getElementById("status").textContent.includes("done"), null,
                             { timeout: 20000 }).catch(() => {});  // a fast machine may finish in between
  await waitDone(page, statusBefore);
  await page.waitForFunction(async () => (await (await fetch(api("/state"))).json()).frame.done, null,
                             { polling: 100, timeout: 60000 });
  await page.waitForTimeout(300);
  const orbited = await pixelsOf(page);
  let changed = 0;
  for (let i = 0; i < orbited.data.length; ++i) changed += orbited.data[i] !== shown.data[i] ? 1 : 0;
  check(changed > orbited.data.length / 20, `the drag moved the camera (${changed} of ${orbited.data.length} bytes changed)`);
  const state = await page.evaluate(async (u) => (await fetch(new URL("/state" + new URL(u).search, u))).json(), url);
  check(state.frame.done && state.frame.spp === SPP, `the orbited view refined to ${SPP} spp again`);
  await page.screenshot({ path: path.join(artifacts, "2-orbited.png") });
  // The second tab follows the camera moved in the first (its own moves start from there).
  await second.waitForFunction((o) => camera.origin.every((v, i) => Math.abs(v - o[i]) < 1e-6), state.camera.origin,
                               { timeout: 10000 });
  console.log("ok: the second tab took the camera moved in the first");
  await second.close();

  // 4. A click shows explain's story for that pixel at the current camera.
  const px = 40, py = 30;
  await page.mouse.click(box.x + (px + 0.5) * box.width / WIDTH, box.y + (py + 0.5) * box.height / HEIGHT);
  await page.waitForFunction(() => document.querySelector("#stories .story h3") !== null, null, { timeout: 30000 });
  const heading = await page.locator("#stories .story h3").first().textContent();
  const story = await page.locator("#stories .story pre").first().textContent();
  check(heading.startsWith(`1: pixel (${px}, ${py}), sample 0: L = [`), `the panel names the clicked pixel: ${heading}`);
  check(story.length > 100 && (await page.locator("#stories .story img").count()) === 1,
        "the panel shows the story's text and its SVG");
  // The same pixel explained by the command line at the orbited camera.
  const c = state.camera;
  const sceneJson = JSON.parse(readFileSync(scene, "utf8"));
  sceneJson.camera = { origin: c.origin, look_at: c.look_at, up: c.up, fov: c.fov };
  for (const o of sceneJson.objects ?? []) if (o.file) o.file = path.resolve(path.dirname(scene), o.file);
  const moved = path.join(work, "moved.json");
  writeFileSync(moved, JSON.stringify(sceneJson));
  const cli = JSON.parse(runSombra(["explain", moved, String(px), String(py), ...common, "--json"]));
  const shownValue = heading.slice(heading.indexOf("[") + 1, heading.indexOf("]")).split(",").map(Number);
  const close = cli.value.every((v, i) => Math.abs(v - shownValue[i]) <= 1e-5 * Math.max(1, Math.abs(v)));
  check(close, `the panel's value [${shownValue}] is explain's [${cli.value.map((v) => v.toPrecision(6))}]`);
  await page.screenshot({ path: path.join(artifacts, "3-explained.png") });

  // 5. The denoise switch: the passes start again, gathering the denoiser's
  // layers, and the newest finished pass is shown denoised, to the last.
  await page.locator("#denoise").check();
  await page.waitForFunction((spp) => document.getElementById("status").textContent.endsWith(
    `done · denoised at ${spp} spp`), SPP, { timeout: 60000 });
  await page.waitForTimeout(300);
  const denoised = await pixelsOf(page);
  const denoisedReference = path.join(work, "denoised.png");
  runSombra(["render", moved, ...common, "--denoise", "-o", denoisedReference, "--quiet"]);
  const denoisedRef = await pixelsOf(page, "data:image/png;base64," + readFileSync(denoisedReference).toString("base64"));
  worst = 0;
  for (let i = 0; i < denoised.data.length; ++i) worst = Math.max(worst, Math.abs(denoised.data[i] - denoisedRef.data[i]));
  check(worst <= 1, `with the switch on the page shows sombra render --denoise's image (largest difference ${worst})`);
  check(denoised.data.some((v, i) => Math.abs(v - orbited.data[i]) > 1), "the denoised image is not the raw one");
  await page.screenshot({ path: path.join(artifacts, "4-denoised.png") });
  await page.locator("#denoise").uncheck();
  await page.waitForFunction(() => !document.getElementById("status").textContent.includes("denois") &&
                                   shownImage.startsWith("p"), null, { timeout: 20000 });
  await page.waitForTimeout(300);
  const raw = await pixelsOf(page);
  check(raw.data.every((v, i) => v === orbited.data[i]), "with the switch off the page shows the raw image again");

  // 5b. A second click compares: two stories side by side, both pixels
  // marked; once the camera moves the marks go (they were of the old view)
  // and each story says the view has moved.
  await page.mouse.click(box.x + (10 + 0.5) * box.width / WIDTH, box.y + (12 + 0.5) * box.height / HEIGHT);
  await page.waitForFunction(() => document.querySelectorAll("#stories .story pre").length === 2 &&
                                   document.querySelectorAll("#stories .story h3")[1].textContent.startsWith("2: pixel (10, 12)"),
                             null, { timeout: 30000 });
  const [left, right] = await page.locator("#stories .story").evaluateAll((divs) => divs.map((d) => d.getBoundingClientRect().toJSON()));
  check(Math.abs(left.top - right.top) < 1 && right.left >= left.right - 1,
        `the two stories stand side by side (${Math.round(left.left)},${Math.round(left.top)} and ${Math.round(right.left)},${Math.round(right.top)})`);
  const marked = () => page.evaluate(() => {
    const c = document.getElementById("marks");
    return c.getContext("2d").getImageData(0, 0, c.width, c.height).data.some((v, i) => i % 4 === 3 && v > 0);
  });
  check(await marked(), "both clicked pixels are marked");
  await page.screenshot({ path: path.join(artifacts, "5-compared.png") });
  await page.keyboard.press("ArrowLeft");
  await page.waitForFunction(() => document.querySelector("#stories .story .moved").textContent !== "", null, { timeout: 10000 });
  check(!(await marked()), "after the camera moved the old marks are gone");

  // 6. An orthographic camera (a glTF file's: a 2 × 2 square seen square on
  // from z = 4, ymag 1.5) zooms by its half-height.
  const square = new Float32Array([-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]);
  const corners = new Uint16Array([0, 1, 2, 0, 2, 3]);
  const bytes = Buffer.concat([Buffer.from(square.buffer), Buffer.from(corners.buffer)]);
  const gltf = path.join(work, "orthographic.gltf");
  writeFileSync(gltf, JSON.stringify({
    asset: { version: "2.0" }, scene: 0, scenes: [{ nodes: [0, 1] }],
    nodes: [{ mesh: 0 }, { camera: 0, translation: [0, 0, 4] }],
    cameras: [{ type: "orthographic", orthographic: { xmag: 2, ymag: 1.5, znear: 0.1, zfar: 100 } }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    buffers: [{ byteLength: bytes.length, uri: "data:application/octet-stream;base64," + bytes.toString("base64") }],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 48 }, { buffer: 0, byteOffset: 48, byteLength: 12 }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 4, type: "VEC3", min: [-1, -1, 0], max: [1, 1, 0] },
      { bufferView: 1, componentType: 5123, count: 6, type: "SCALAR" }],
  }));
  const ortho = await serve(gltf);
  try {
    const view = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    view.on("pageerror", (e) => fail(`the page threw: ${e.message}`));
    await view.goto(ortho.address);
    await waitDone(view);
    await view.waitForFunction(() => document.getElementById("view").naturalWidth > 0);
    await view.waitForTimeout(300);
    const before = await pixelsOf(view);
    const stateOf = () => view.evaluate(async () => (await fetch(api("/state"))).json());
    const first = await stateOf();
    check(first.camera.projection === "orthographic" && first.camera.half_height === 1.5,
          `the viewer's state says orthographic, half-height 1.5 (${JSON.stringify(first.camera)})`);
    const statusBefore = await view.locator("#status").textContent();
    await view.keyboard.press("+");
    await view.waitForFunction(() => !document.getElementById("status").textContent.includes("done"), null,
                               { timeout: 20000 }).catch(() => {});
    await waitDone(view, statusBefore);
    await view.waitForTimeout(300);
    const zoomed = await stateOf();
    check(Math.abs(zoomed.camera.half_height - 1.5 / 1.1) < 1e-5 &&
          zoomed.camera.origin.every((v, i) => v === first.camera.origin[i]),
          `+ zoomed by the half-height (${zoomed.camera.half_height}), the origin where it was`);
    const after = await pixelsOf(view);
    // The square's pixels: brighter than the quick look's grey background (the corner's).
    const lit = (img) => {
      let n = 0;
      for (let i = 0; i < img.data.length; i += 4) n += img.data[i] > img.data[0] + 20 ? 1 : 0;
      return n;
    };
    check(lit(after) > 1.1 * lit(before), `the square grew on screen (${lit(before)} → ${lit(after)} pixels)`);
    await view.screenshot({ path: path.join(artifacts, "5-orthographic.png") });
  } finally {
    ortho.child.kill("SIGTERM");
  }
  passed = true;
} finally {
  await browser.close();
  // 7. A signal ends the server at once and frees the port.
  const started = Date.now();
  server.kill("SIGTERM");
  const code = await new Promise((r) => (server.exitCode !== null ? r(server.exitCode) : server.on("exit", r)));
  if (passed) {
    check(code === 0 && Date.now() - started < 2000, `SIGTERM ended the server (status ${code}, ${Date.now() - started} ms)`);
    // Freed as a user needs it: a new `sombra view --port P` serves there.
    const again = spawnSync("timeout", ["-s", "TERM", "3", exe, "view", scene, ...common, "--port", String(port)],
                            { encoding: "utf8" });
    check(again.stdout.startsWith(`http://127.0.0.1:${port}/`),
          `port ${port} is free again: a new server listens there (${again.stderr.trim() || "no error"})`);
  }
  rmSync(work, { recursive: true, force: true });
}
console.log("1 passed, 0 failed");
