// radflux view: the page's script. A job's view (/job/ID/) gets its mesh once, then
// progress as Server-Sent Events ("events") and the newest snapshot ("snapshot", float16
// B per patch) whenever an event says a newer one exists: one fetch at a time, so a slow
// tab skips snapshots instead of queueing them. The job list (/jobs/) and a saved result
// (/glb/) reuse the page. What the page shows is also in window.radfluxView (for tests).
'use strict';
(function () {
  const view = window.radfluxView = {
    snapshots: [],       // iterations of the snapshots shown, in order
    residuals: [],       // [iteration, residual] points of the plot
    radiosity: null,     // Float32Array: B (W/m^2) per patch and band, of the newest snapshot
    colours: null,       // Float32Array: displayed sRGB in [0, 1] per patch and band
    exposureScale: 1,    // the snapshot's auto exposure (AutoExposureScale of B/pi)
    stops: 0,            // the exposure control
    plotPoints: 0,       // points drawn in the residual plot
    state: '', ended: false, error: '', ready: false,
    lightmapped: 0,      // meshes of a saved result drawn with radflux's baked lightmap
    lightmapStrength: 1, // their emissive strength (the texture's scale, >= 1)
  };
  const $ = (id) => document.getElementById(id);
  const hide = (id) => $(id).classList.add('hidden');

  function halfToFloat(h) {
    const sign = h & 0x8000 ? -1 : 1, e = (h >> 10) & 0x1f, f = h & 0x3ff;
    if (e === 0) return sign * Math.pow(2, -14) * (f / 1024);
    if (e === 31) return f ? NaN : sign * Infinity;
    return sign * Math.pow(2, e - 15) * (1 + f / 1024);
  }
  // The PNG writer's mapping (solver/output/tone_map.h): clamp(radiance * scale * 2^stops),
  // then the sRGB transfer curve.
  function srgb(x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * Math.pow(x, 1 / 2.4) - 0.055; }

  function setupScene() {
    const box = $('scene');
    const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio);
    box.appendChild(renderer.domElement);
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0x101114);
    const camera = new THREE.PerspectiveCamera(39.3, 1, 0.01, 1e6);
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    let dirty = true;
    const three = { renderer, scene, camera, controls, redraw: () => { dirty = true; } };
    function resize() {
      renderer.setSize(box.clientWidth, box.clientHeight);
      camera.aspect = box.clientWidth / Math.max(1, box.clientHeight);
      camera.updateProjectionMatrix();
      dirty = true;
    }
    window.addEventListener('resize', resize);
    controls.addEventListener('change', three.redraw);
    resize();
    (function loop() {
      requestAnimationFrame(loop);
      if (dirty) { renderer.render(scene, camera); dirty = false; }
    })();
    return three;
  }

  // The PNG writer's default camera: on -z of the bounding box, looking at its centre.
  function frame(three, bounds) {
    const c = bounds.getCenter(new THREE.Vector3()), size = bounds.getSize(new THREE.Vector3());
    const half = Math.max(size.y, size.x / three.camera.aspect) / 2;
    const d = half / Math.tan(THREE.Math.degToRad(three.camera.fov / 2));
    three.camera.position.set(c.x, c.y, bounds.min.z - d);
    three.camera.near = d / 100;
    three.camera.far = d * 100 + size.length();
    three.camera.updateProjectionMatrix();
    three.controls.target.copy(c);
    three.controls.update();
  }

  // The mesh of "mesh" (view_feed.cc MeshBytes): six vertices (two triangles) per patch.
  function buildMesh(three, buffer) {
    const header = new DataView(buffer);
    const nv = header.getUint32(0, true), np = header.getUint32(4, true);
    const xyz = new Float32Array(buffer, 8, 3 * nv);
    const corners = new Uint32Array(buffer, 8 + 12 * nv, 4 * np);
    const positions = new Float32Array(18 * np);
    const order = [0, 1, 2, 0, 2, 3];
    for (let p = 0; p < np; ++p) {
      for (let k = 0; k < 6; ++k) {
        const v = corners[4 * p + order[k]];
        positions.set(xyz.subarray(3 * v, 3 * v + 3), 18 * p + 3 * k);
      }
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(18 * np).fill(0.15), 3));
    geometry.computeBoundingBox();
    const material = new THREE.MeshBasicMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide });
    const mesh = new THREE.Mesh(geometry, material);
    three.scene.add(mesh);
    frame(three, geometry.boundingBox);
    return mesh;
  }

  function applyColours(three, mesh) {
    if (!view.radiosity || !mesh) return;
    const k = view.exposureScale * Math.pow(2, view.stops) / Math.PI;
    const colours = new Float32Array(view.radiosity.length);
    for (let i = 0; i < colours.length; ++i) {
      colours[i] = srgb(Math.min(1, Math.max(0, view.radiosity[i] * k)));
    }
    view.colours = colours;
    const attribute = mesh.geometry.attributes.color;
    for (let p = 0; p < colours.length / 3; ++p) {
      for (let v = 0; v < 6; ++v) attribute.array.set(colours.subarray(3 * p, 3 * p + 3), 18 * p + 3 * v);
    }
    attribute.needsUpdate = true;
    three.redraw();
  }

  // log10(residual) against iteration, on a plain canvas.
  function drawPlot() {
    const canvas = $('plot'), g = canvas.getContext('2d'), pts = view.residuals;
    const w = canvas.width, h = canvas.height, pad = 28;
    g.clearRect(0, 0, w, h);
    g.fillStyle = '#888';
    g.font = '10px sans-serif';
    if (pts.length === 0) { view.plotPoints = 0; g.fillText('no iterations yet', pad, h / 2); return; }
    const xs = pts.map((p) => p[0]), ys = pts.map((p) => Math.log10(p[1]));
    const x0 = Math.min(...xs), x1 = Math.max(x0 + 1, ...xs);
    const y0 = Math.floor(Math.min(...ys)), y1 = Math.max(y0 + 1, Math.ceil(Math.max(...ys)));
    const X = (x) => pad + (x - x0) / (x1 - x0) * (w - pad - 6);
    const Y = (y) => 6 + (y1 - y) / (y1 - y0) * (h - pad);
    for (let y = y0; y <= y1; ++y) g.fillText('1e' + y, 0, Y(y) + 3);
    g.fillText(String(x0), pad, h - 4);
    g.fillText(String(x1), w - 24, h - 4);
    g.strokeStyle = '#e8a33d';
    g.beginPath();
    pts.forEach((p, i) => (i ? g.lineTo : g.moveTo).call(g, X(p[0]), Y(Math.log10(p[1]))));
    g.stroke();
    g.fillStyle = '#e8a33d';
    pts.forEach((p) => g.fillRect(X(p[0]) - 1.5, Y(Math.log10(p[1])) - 1.5, 3, 3));
    view.plotPoints = pts.length;
  }

  function showProgress(m) {
    view.state = m.state || view.state;
    $('phase').textContent = m.phase || m.state || '';
    $('fill').style.width = (m.fraction >= 0 ? 100 * m.fraction : 0) + '%';
    $('detail').textContent = m.detail || '';
    if (m.error) {
      view.error = m.error;
      $('detail').textContent = m.error;
      $('detail').className = 'error';
    }
  }

  function finish(m) {
    view.ended = true;
    if (m.has_report) {
      fetch('report').then((r) => r.text()).then((text) => {
        try { text = JSON.stringify(JSON.parse(text), null, 1); } catch (e) { /* as sent */ }
        $('report').textContent = text;
      });
    } else {
      $('report').textContent = '(no report: the job ' + (view.error ? 'view failed' : 'did not succeed') + ')';
    }
    if (m.has_glb) $('links').innerHTML = '<h2>result</h2><a href="result.glb" download>download the lit mesh (.glb)</a>';
  }

  function jobView(three) {
    let mesh = null, have = 0, wanted = 0, fetching = false;
    function fetchSnapshot() {
      if (fetching || !mesh || wanted <= have) return;
      fetching = true;
      fetch('snapshot', { cache: 'no-store' }).then((r) => {
        if (r.status !== 200) return null;
        const serial = +r.headers.get('X-Serial'), iteration = +r.headers.get('X-Iteration');
        const scale = +r.headers.get('X-Exposure-Scale');
        return r.arrayBuffer().then((bytes) => {
          const halves = new Uint16Array(bytes), b = new Float32Array(halves.length);
          for (let i = 0; i < b.length; ++i) b[i] = halfToFloat(halves[i]);
          have = serial;
          view.radiosity = b;
          view.exposureScale = scale;
          view.snapshots.push(iteration);
          applyColours(three, mesh);
        });
      }).finally(() => { fetching = false; fetchSnapshot(); });
    }
    fetch('info').then((r) => r.json()).then((info) => {
      $('title').textContent = info.job_id || '';
      $('options').textContent = JSON.stringify(info.options || {}, null, 1) + '\npatches: ' + info.patches;
    });
    fetch('mesh').then((r) => r.arrayBuffer()).then((bytes) => {
      if (bytes.byteLength >= 8) mesh = buildMesh(three, bytes);
      view.ready = true;
      fetchSnapshot();
    });
    $('exposure').addEventListener('input', () => {
      view.stops = +$('exposure').value;
      $('stops').textContent = view.stops;
      applyColours(three, mesh);
    });
    const events = new EventSource('events');
    events.onmessage = (e) => {
      const m = JSON.parse(e.data);
      showProgress(m);
      if (m.residuals.length) { view.residuals.push(...m.residuals); drawPlot(); }
      wanted = m.snapshot_serial;
      fetchSnapshot();
      if (m.ended) { events.close(); finish(m); }
    };
    drawPlot();
  }

  function jobList() {
    ['scene', 'live', 'exposure-box', 'plot-box', 'options-box', 'report-box'].forEach(hide);
    $('side').style.width = '100%';
    $('title').textContent = 'radflux jobs';
    fetch('/api/jobs').then((r) => r.ok ? r.json() : r.text().then((t) => { throw new Error(t); }))
      .then((jobs) => {
        const rows = jobs.map((j) => '<tr><td><a href="/job/' + j.job_id + '/">' + j.job_id + '</a></td><td>' +
          j.state.replace('JOB_STATE_', '').toLowerCase() + (j.not_converged ? ' (not converged)' : '') +
          '</td><td>' + j.phase.replace('PHASE_', '').toLowerCase() + '</td><td>' + j.patches + '</td></tr>');
        $('jobs').innerHTML = '<table><tr><th>job</th><th>state</th><th>phase</th><th>patches</th></tr>' +
          rows.join('') + '</table>';
        view.ready = true;
      }).catch((e) => { $('jobs').textContent = String(e); $('jobs').className = 'error'; });
  }

  // radflux's lightmapped GLB (solver/output/lightmap_gltf.h: a material whose extras hold
  // radflux_radiance_scale) shows its baked light as an emissive texture on TEXCOORD_1 with
  // KHR_materials_emissive_strength. This three.js (r111) samples every map but the aoMap and
  // lightMap on TEXCOORD_0 and ignores that extension, so the mesh's first UV set is replaced
  // by its second (TEXCOORD_0 maps nothing else in this material) and the emissive colour
  // scaled by the strength. No mipmaps: the atlas's gutter guards bilinear filtering only,
  // coarser levels would mix neighbouring charts.
  function useLightmap(mesh) {
    const material = mesh.material, geometry = mesh.geometry;
    if (!material.emissiveMap || material.userData.radflux_radiance_scale === undefined) return;
    if (!geometry.attributes.uv2) { view.error = 'lightmap material without TEXCOORD_1'; return; }
    geometry.setAttribute('uv', geometry.attributes.uv2);
    const strength = ((material.userData.gltfExtensions || {}).KHR_materials_emissive_strength || {}).emissiveStrength;
    view.lightmapStrength = strength === undefined ? 1 : strength;
    material.emissive.multiplyScalar(view.lightmapStrength);
    material.emissiveMap.generateMipmaps = false;
    material.emissiveMap.minFilter = THREE.LinearFilter;
    material.emissiveMap.needsUpdate = true;
    material.needsUpdate = true;
    view.lightmapped += 1;
  }

  function savedResult(three) {
    ['live', 'exposure-box', 'plot-box', 'options-box', 'report-box'].forEach(hide);
    $('title').textContent = 'saved result';
    three.renderer.outputEncoding = THREE.sRGBEncoding;  // COLOR_0 is linear
    new THREE.GLTFLoader().load('result.glb', (gltf) => {
      gltf.scene.traverse((o) => { if (o.isMesh) useLightmap(o); });
      three.scene.add(gltf.scene);
      frame(three, new THREE.Box3().setFromObject(gltf.scene));
      three.redraw();
      view.ready = true;
    }, undefined, (e) => { view.error = String(e); });
  }

  const path = window.location.pathname;
  if (path.startsWith('/jobs/')) jobList();
  else if (path.startsWith('/glb/')) savedResult(setupScene());
  else jobView(setupScene());
})();
