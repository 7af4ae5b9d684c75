// The teaching page of `ccdlab export --html`: the data (CCDLAB, teaching_data.hpp) drawn with three.js.
// Everything is computed here from integers on the scene's grid; nothing is fetched.
"use strict";
(function () {
  const cspViolations = [];  // what the page's Content-Security-Policy refused (the self-test reports them)
  document.addEventListener("securitypolicyviolation", (e) => cspViolations.push(e.blockedURI));
  const D = CCDLAB;
  const q = D.grid.quantum, O = D.grid.origin;
  const $ = (id) => document.getElementById(id);

  // ---- decoding -------------------------------------------------------------------------------------------
  const frames = D.mesh.frames.map((f) => {
    const x = new Float64Array(f.length);
    for (let i = 0; i < f.length; ++i) x[i] = O[i % 3] + f[i] * q;
    return x;
  });
  const faces = D.mesh.faces, nfaces = faces.length / 3;
  const vtx = (x, v) => [x[3 * v], x[3 * v + 1], x[3 * v + 2]];
  const lerp = (a, b, t) => [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])];
  const at = (s, v, t) => lerp(vtx(frames[s], v), vtx(frames[s + 1], v), t);
  const steps = D.steps.length;

  // ---- k-DOP polyhedra: the intersection of the K half-spaces, vertex by vertex (kdop_polyhedron.hpp) --------
  function polyhedron(axes, slab) {
    const h = axes.length, planes = [];
    for (let i = 0; i < h; ++i) {
      const d = axes[i], o = d[0] * O[0] + d[1] * O[1] + d[2] * O[2];
      planes.push({ n: d, c: o + slab[h + i] * q, axis: i });  // d·x ≤ max
      planes.push({ n: [-d[0], -d[1], -d[2]], c: -(o + slab[i] * q), axis: i });  // −d·x ≤ −min
    }
    const size = Math.max(1e-12, Math.abs(slab[h] - slab[0]) * q);
    const eps = 1e-7 * size + 1e-12;
    const verts = [], onPlane = planes.map(() => []);
    for (let i = 0; i < planes.length; ++i)
      for (let j = i + 1; j < planes.length; ++j) {
        if (planes[i].axis === planes[j].axis) continue;
        for (let k = j + 1; k < planes.length; ++k) {
          if (planes[k].axis === planes[i].axis || planes[k].axis === planes[j].axis) continue;
          const a = planes[i].n, b = planes[j].n, c = planes[k].n;
          const det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
          if (Math.abs(det) < 1e-9) continue;
          const bc = [b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]];
          const ca = [c[1] * a[2] - c[2] * a[1], c[2] * a[0] - c[0] * a[2], c[0] * a[1] - c[1] * a[0]];
          const ab = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
          const p = [0, 1, 2].map((e) => (planes[i].c * bc[e] + planes[j].c * ca[e] + planes[k].c * ab[e]) / det);
          let inside = true;
          for (const pl of planes)
            if (pl.n[0] * p[0] + pl.n[1] * p[1] + pl.n[2] * p[2] > pl.c + eps * Math.hypot(...pl.n)) { inside = false; break; }
          if (!inside) continue;
          const id = verts.length;
          verts.push(p);
          for (let m = 0; m < planes.length; ++m) {
            const pl = planes[m];
            if (Math.abs(pl.n[0] * p[0] + pl.n[1] * p[1] + pl.n[2] * p[2] - pl.c) <= eps * Math.hypot(...pl.n)) onPlane[m].push(id);
          }
        }
      }
    const polys = [];
    onPlane.forEach((ids, m) => {
      if (ids.length < 3) return;
      const c = [0, 1, 2].map((e) => ids.reduce((s, id) => s + verts[id][e], 0) / ids.length);
      const n = planes[m].n, u = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
      const e1 = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]];
      const e2 = [n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]];
      const ang = (id) => { const d = [0, 1, 2].map((e) => verts[id][e] - c[e]); return Math.atan2(d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2], d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2]); };
      polys.push([...new Set(ids)].sort((a, b) => ang(a) - ang(b)).map((id) => verts[id]));
    });
    return polys;
  }
  function slabCentre(slab, h) {  // the box part (axes 0..2 are x, y, z)
    return [0, 1, 2].map((a) => O[a] + 0.5 * (slab[a] + slab[h + a]) * q);
  }

  // ---- scene ----------------------------------------------------------------------------------------------
  const view = $("view");
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  const camera = new THREE.PerspectiveCamera(40, 1, 1e-3, 1e3);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.set(1, 2, 3);
  scene.add(sun);
  {  // frame the scene: the bounding box of every frame
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const x of frames) for (let i = 0; i < x.length; ++i) { lo[i % 3] = Math.min(lo[i % 3], x[i]); hi[i % 3] = Math.max(hi[i % 3], x[i]); }
    const c = lo.map((l, a) => 0.5 * (l + hi[a])), r = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 || 1;
    controls.target.set(c[0], c[1], c[2]);
    camera.position.set(c[0] + 1.6 * r, c[1] - 2.2 * r, c[2] + 1.4 * r);
    camera.up.set(0, 0, 1);
    camera.near = r / 100, camera.far = r * 100;
    controls.update();
  }
  function resize() {
    const w = view.clientWidth, h = view.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
    render();
  }
  function render() { renderer.render(scene, camera); }
  controls.addEventListener("change", render);
  window.addEventListener("resize", resize);

  const layers = {};  // name -> THREE.Object3D currently shown
  function setLayer(name, obj) {
    if (layers[name]) { scene.remove(layers[name]); layers[name].traverse((o) => { if (o.geometry) o.geometry.dispose(); }); }
    layers[name] = obj;
    if (obj) scene.add(obj);
  }
  function lines(points, colors, opts = {}) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.Float32BufferAttribute(points.flat(), 3));
    if (colors) g.setAttribute("color", new THREE.Float32BufferAttribute(colors.flat(), 3));
    return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: !!colors, color: opts.color || 0xffffff, transparent: !!opts.opacity, opacity: opts.opacity || 1 }));
  }
  function polyMesh(polys, color, opacity) {
    const tri = [], edges = [];
    for (const poly of polys) {
      for (let i = 1; i + 1 < poly.length; ++i) tri.push(poly[0], poly[i], poly[i + 1]);
      for (let i = 0; i < poly.length; ++i) edges.push(poly[i], poly[(i + 1) % poly.length]);
    }
    const group = new THREE.Group();
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.Float32BufferAttribute(tri.flat(), 3));
    g.computeVertexNormals();
    group.add(new THREE.Mesh(g, new THREE.MeshLambertMaterial({ color, transparent: true, opacity, side: THREE.DoubleSide, depthWrite: false })));
    group.add(lines(edges, null, { color }));
    return group;
  }
  const heat = (n, max) => {  // white → orange → dark red by contacts per triangle
    if (n <= 0) return [0.78, 0.82, 0.88];
    const t = Math.min(1, n / Math.max(max, 1));
    return [1, 0.75 - 0.55 * t, 0.35 - 0.3 * t];
  };

  // ---- state ----------------------------------------------------------------------------------------------
  const state = { step: 0, k: String(D.meta.k), depth: Math.min(2, D.meta.levels - 1), mode: "scene", walk: 0, visit: 0 };
  const pickable = [];  // { object, items: [info per index], kind }

  // The mesh at a frame, each face coloured by faceColors(f); faces for which faint(f) holds are drawn see-through
  // (the walk-through shows its triangles through the rest).
  function drawMesh(frame, faceColors, faint = () => false) {
    const x = frames[frame], group = new THREE.Group();
    for (const see of [false, true]) {
      const pos = [], col = [], edges = [];
      for (let f = 0; f < nfaces; ++f) {
        if (faint(f) !== see) continue;
        for (let j = 0; j < 3; ++j) {
          pos.push(...vtx(x, faces[3 * f + j]));
          col.push(...faceColors(f));
          edges.push(vtx(x, faces[3 * f + j]), vtx(x, faces[3 * f + (j + 1) % 3]));
        }
      }
      if (!pos.length) continue;
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.Float32BufferAttribute(pos, 3));
      g.setAttribute("color", new THREE.Float32BufferAttribute(col, 3));
      g.computeVertexNormals();
      group.add(new THREE.Mesh(g, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide, polygonOffset: true,
        polygonOffsetFactor: 1, polygonOffsetUnits: 1, transparent: see, opacity: see ? 0.12 : 1, depthWrite: !see })));
      group.add(lines(edges, null, { color: 0x556070, opacity: see ? 0.08 : 0.35 }));
    }
    return group;
  }

  const polyCache = new Map();
  function nodePolys(k, key, slab) {
    if (!polyCache.has(key)) polyCache.set(key, polyhedron(D.axes[k], slab));
    return polyCache.get(key);
  }

  function drawScene() {
    const s = state.step, kd = D.ks_data[state.k][s], st = D.steps[s];
    pickable.length = 0;
    // mesh
    if ($("show-mesh").checked) {
      const fc = st.face_contacts, max = Math.max(...fc);
      setLayer("mesh", drawMesh(s, (f) => heat(fc[f], max)));
    } else setLayer("mesh", null);
    // BVH at one depth, every body
    if ($("show-bvh").checked) {
      const group = new THREE.Group();
      D.bodies.forEach((topo, b) => {
        const polys = [];
        topo.depth.forEach((d, n) => {
          if (d !== state.depth || !kd.slabs[b][n]) return;
          polys.push(...nodePolys(state.k, `${state.k}/${s}/${b}/${n}`, kd.slabs[b][n]));
        });
        if (polys.length) group.add(polyMesh(polys, b === 0 ? 0x3a7bd5 : 0x8e44ad, 0.12));
      });
      setLayer("bvh", group);
    } else setLayer("bvh", null);
    // the front (the config's K: it is the front scheduler's), a line between the centres of a pair's volumes
    const main = D.ks_data[String(D.meta.k)][s];
    const show = [$("show-kept").checked, $("show-sprouted").checked, $("show-pruned").checked];
    const colors = [[0.55, 0.55, 0.55], [0.12, 0.44, 0.82], [0.84, 0.15, 0.16]];
    const fp = [], fc = [], items = [];
    const centre = (b, n) => [0, 1, 2].map((a) => O[a] + main.centres[b][3 * n + a] * q);
    main.fronts.forEach((pass, p) => {
      const [ba, bb] = pass.bodies;
      for (const [a, b, change, overlapped] of pass.nodes) {
        if (!show[change]) continue;
        const ca = centre(ba, a), cb = centre(bb, b);
        fp.push(ca, a === b && ba === bb ? [ca[0] + 1e-6, ca[1], ca[2]] : cb);
        fc.push(colors[change], colors[change]);
        items.push({ pass: p, self: pass.self, a, b, bodies: pass.bodies, change, overlapped });
      }
    });
    if (fp.length) {
      const obj = lines(fp, fc);
      setLayer("front", obj);
      pickable.push({ object: obj, items, kind: "front", perItem: 2 });
    } else setLayer("front", null);
    // candidate pairs: a line between the triangles' centroids at the step's start
    if ($("show-candidates").checked) {
      const x = frames[s], cen = (f) => [0, 1, 2].map((a) => (x[3 * faces[3 * f] + a] + x[3 * faces[3 * f + 1] + a] + x[3 * faces[3 * f + 2] + a]) / 3);
      const pts = [];
      for (const [a, b] of main.candidate_pairs) pts.push(cen(a), cen(b));
      setLayer("candidates", lines(pts, null, { color: 0x2ca02c, opacity: 0.5 }));
    } else setLayer("candidates", null);
    // contacts at their time of contact
    if ($("show-contacts").checked) {
      const pts = [], feat = [], items2 = [];
      for (const c of st.contacts) {
        const p = c.v.map((v) => at(s, v, c.toi));
        let point;
        if (c.kind === "vf") { point = p[0]; feat.push(p[1], p[2], p[2], p[3], p[3], p[1]); }
        else { point = lerp(p[0], p[1], c.coords[0]); feat.push(p[0], p[1], p[2], p[3]); }
        pts.push(point);
        items2.push(c);
      }
      const group = new THREE.Group();
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.Float32BufferAttribute(pts.flat(), 3));
      const points = new THREE.Points(g, new THREE.PointsMaterial({ color: 0xff7f0e, size: 6, sizeAttenuation: false }));
      group.add(points, lines(feat, null, { color: 0xd35400, opacity: 0.7 }));
      setLayer("contacts", group);
      pickable.push({ object: points, items: items2, kind: "contact", perItem: 1 });
    } else setLayer("contacts", null);
    const kc = kd;
    $("step-label").textContent = `step ${s} (frame ${s} → ${s + 1})`;
    $("counts").textContent = `K = ${state.k}: ${kc.bv_tests} BV tests, ${kc.candidates} candidate pairs, ${kc.contacts} contacts, ${kc.ms.toFixed(2)} ms` +
      ` — front (${D.meta.k}-DOP): ${main.fronts.reduce((n, p) => n + p.nodes.length, 0)} node pairs`;
    $("depth-label").textContent = String(state.depth);
    render();
  }

  // ---- the walk-through ------------------------------------------------------------------------------------
  const W = D.walk;
  const walkFaces = new Set();
  if (W && W.orders) D.bodies[W.body].face.forEach((f, n) => { if (f >= 0 && W.slabs[n]) walkFaces.add(f); });
  function focusOnWalk() {  // the camera on the walked triangles, from where it looks now
    const x = frames[W.step], lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const f of walkFaces) for (let j = 0; j < 3; ++j) { const p = vtx(x, faces[3 * f + j]); for (let a = 0; a < 3; ++a) { lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]); } }
    const c = lo.map((l, a) => 0.5 * (l + hi[a])), r = Math.max(1e-9, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
    const dir = camera.position.clone().sub(controls.target).normalize();
    controls.target.set(c[0], c[1], c[2]);
    camera.position.set(c[0] + 3 * r * dir.x, c[1] + 3 * r * dir.y, c[2] + 3 * r * dir.z);
    controls.update();
  }
  function drawWalk() {
    pickable.length = 0;
    const order = W.orders[state.walk], s = W.step;
    setLayer("mesh", drawMesh(s, (f) => (walkFaces.has(f) ? [1, 0.7, 0.3] : [0.75, 0.78, 0.82]), (f) => !walkFaces.has(f)));
    setLayer("front", null); setLayer("candidates", null); setLayer("contacts", null);
    const i = Math.min(state.visit, order.visits.length - 1), h = D.axes[String(D.meta.k)].length;
    const group = new THREE.Group();
    let tests = 0, overlaps = 0, cands = 0;
    const perThread = new Array(order.threads).fill(0);
    const log = [];
    for (let j = 0; j <= i; ++j) {
      const [a, b, flags, task, thread] = order.visits[j];
      tests += flags & 1; overlaps += (flags >> 1) & 1; cands += (flags >> 2) & 1; perThread[thread] += 1;
      if (j > i - 40) log.push(`${String(j).padStart(4)}  (${a}, ${b})${a === b ? " self" : ""}  ${flags & 4 ? "candidate" : flags & 2 ? "overlap" : flags & 1 ? "apart" : "opens"}  ${task < 0 ? "top" : "task " + task}  thread ${thread}`);
    }
    if (i >= 0) {
      const [a, b, flags] = order.visits[i];
      const color = flags & 4 ? 0xff7f0e : flags & 2 ? 0x2ca02c : 0x999999;
      group.add(polyMesh(polyhedron(D.axes[String(D.meta.k)], W.slabs[a]), 0xd62728, 0.18));
      if (b !== a) group.add(polyMesh(polyhedron(D.axes[String(D.meta.k)], W.slabs[b]), 0x1f6fd0, 0.18));
      const ca = slabCentre(W.slabs[a], h), cb = slabCentre(W.slabs[b], h);
      group.add(lines([ca, cb], null, { color }));
    }
    setLayer("bvh", group);
    $("visit-label").textContent = `${i + 1} / ${order.visits.length}`;
    $("walk-counts").textContent = `${order.scheduler}: ${tests} BV tests, ${overlaps} overlapping, ${cands} candidates so far; ` +
      (order.threads > 1 ? `visits per thread ${perThread.join(" / ")}; ${order.tasks} tasks` : "one thread");
    $("walklog").textContent = log.join("\n");
    $("walklog").scrollTop = $("walklog").scrollHeight;
    render();
  }

  // ---- picking ----------------------------------------------------------------------------------------------
  const ray = new THREE.Raycaster();
  renderer.domElement.addEventListener("click", (ev) => {
    const r = renderer.domElement.getBoundingClientRect();
    const m = new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(m, camera);
    const scale = camera.position.distanceTo(controls.target);
    ray.params.Points.threshold = 0.01 * scale;
    ray.params.Line.threshold = 0.005 * scale;
    for (const p of pickable) {
      const hit = ray.intersectObject(p.object)[0];
      if (!hit) continue;
      const item = p.items[Math.floor(hit.index / p.perItem)];
      if (item) {
        if (p.kind === "contact") select(item);
        else $("info").textContent = describe(p.kind, item), $("info").classList.remove("muted"), setLayer("selected", null), render();
        return;
      }
    }
  });
  // A contact selected: its description, and its features drawn large at the time of contact (the face or the
  // two edges, the contact point).
  function select(c) {
    if (!c) return;
    $("info").textContent = describe("contact", c);
    $("info").classList.remove("muted");
    const s = state.step, p = c.v.map((v) => at(s, v, c.toi));
    const point = c.kind === "vf" ? p[0] : lerp(p[0], p[1], c.coords[0]);
    const group = new THREE.Group();
    group.add(lines(c.kind === "vf" ? [p[1], p[2], p[2], p[3], p[3], p[1]] : [p[0], p[1], p[2], p[3]], null, { color: 0x000000 }));
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.Float32BufferAttribute(point, 3));
    group.add(new THREE.Points(g, new THREE.PointsMaterial({ color: 0x000000, size: 14, sizeAttenuation: false })));
    setLayer("selected", group);
    render();
  }
  function describe(kind, it) {
    const names = D.mesh.bodies;
    if (kind === "contact") {
      const feat = it.kind === "vf" ? `vertex ${it.a} against face ${it.b}` : `edge ${it.a} against edge ${it.b}`;
      const how = it.orphan ? `faces ${it.faces[0]} and ${it.faces[1]} are adjacent: the pair is in the orphan set, tested outside the BVTT`
                            : `BVTT leaf pair (${names[it.bodies[0]]} node ${it.leaves[0]}, ${names[it.bodies[1]]} node ${it.leaves[1]}) → candidate faces (${it.faces[0]}, ${it.faces[1]}), which own the features`;
      return `${it.kind.toUpperCase()} contact: ${feat}\nvertices ${it.v.join(", ")}\ntime of contact ${it.toi.toPrecision(9)} of the step\n` +
             `coords ${it.coords.map((c) => c.toFixed(4)).join(", ")}\n${how}`;
    }
    const change = ["kept (the walk stopped here last step too)", "sprouted (below last step's front: it opened)", "pruned (above last step's front: children merged back)"][it.change];
    const d = (b, n) => D.bodies[b].depth[n];
    return `front node pair of pass ${it.pass}${it.self ? " (self)" : ""}\n${names[it.bodies[0]]} node ${it.a} (depth ${d(it.bodies[0], it.a)}) × ${names[it.bodies[1]]} node ${it.b} (depth ${d(it.bodies[1], it.b)})\n${change}\nlast test: ${it.overlapped ? "overlapping" : "apart"}`;
  }

  // ---- controls ----------------------------------------------------------------------------------------------
  $("meta").textContent = `${D.meta.name}: ${D.meta.scene}; scheduler ${D.meta.scheduler}, tester ${D.meta.tester}; revision ${D.meta.revision}`;
  const stepInput = $("step");
  stepInput.max = String(steps - 1);
  stepInput.addEventListener("input", () => { state.step = +stepInput.value; setLayer("selected", null); drawScene(); });
  const depthInput = $("depth");
  depthInput.max = String(D.meta.levels - 1);
  depthInput.value = String(state.depth);
  depthInput.addEventListener("input", () => { state.depth = +depthInput.value; drawScene(); });
  for (const k of D.meta.ks) {
    const l = document.createElement("label");
    l.innerHTML = `<input type="radio" name="k" value="${k}" ${String(k) === state.k ? "checked" : ""}> ${k}-DOP`;
    l.querySelector("input").addEventListener("change", () => { state.k = String(k); drawScene(); });
    $("k-choice").appendChild(l);
  }
  for (const id of ["show-mesh", "show-bvh", "show-kept", "show-sprouted", "show-pruned", "show-candidates", "show-contacts"])
    $(id).addEventListener("change", drawScene);
  function player(button, input, onTick) {
    let timer = null;
    button.addEventListener("click", () => {
      if (timer) { clearInterval(timer); timer = null; button.textContent = "▶"; return; }
      button.textContent = "❚❚";
      timer = setInterval(() => {
        input.value = String((+input.value + 1) % (+input.max + 1));
        input.dispatchEvent(new Event("input"));
      }, onTick);
    });
  }
  player($("play"), stepInput, 700);
  const visitInput = $("visit");
  visitInput.addEventListener("input", () => { state.visit = +visitInput.value; drawWalk(); });
  player($("walk-play"), visitInput, 250);
  if (W && W.orders) {
    W.orders.forEach((o, i) => {
      const l = document.createElement("label");
      l.innerHTML = `<input type="radio" name="walk" ${i === 0 ? "checked" : ""}> ${o.scheduler}`;
      l.querySelector("input").addEventListener("change", () => {
        state.walk = i; state.visit = 0; visitInput.value = "0"; visitInput.max = String(o.visits.length - 1); drawWalk();
      });
      $("walk-choice").appendChild(l);
    });
    visitInput.max = String(W.orders[0].visits.length - 1);
  } else $("tab-walk").disabled = true;
  function setMode(mode) {
    state.mode = mode;
    $("scene-panel").style.display = mode === "scene" ? "" : "none";
    $("walk-panel").style.display = mode === "walk" ? "" : "none";
    $("tab-scene").classList.toggle("on", mode === "scene");
    $("tab-walk").classList.toggle("on", mode === "walk");
    if (mode === "walk" && !state.focused) focusOnWalk(), state.focused = true;
    if (mode === "scene") drawScene(); else drawWalk();
  }
  $("tab-scene").addEventListener("click", () => setMode("scene"));
  $("tab-walk").addEventListener("click", () => setMode("walk"));

  // The page's state from its address (#step=5&k=6&depth=3&mode=walk&walk=1&visit=40): a link or a screenshot
  // shows the same view.
  const hash = new URLSearchParams(location.hash.slice(1));
  if (hash.has("step")) stepInput.value = String(Math.min(steps - 1, +hash.get("step"))), state.step = +stepInput.value;
  if (hash.has("depth")) depthInput.value = hash.get("depth"), state.depth = +depthInput.value;
  if (hash.has("k") && D.ks_data[hash.get("k")]) {
    state.k = hash.get("k");
    for (const r of document.querySelectorAll('input[name="k"]')) r.checked = r.value === state.k;
  }
  for (const layer of ["mesh", "bvh", "kept", "sprouted", "pruned", "candidates", "contacts"])
    if (hash.has(layer)) $("show-" + layer).checked = hash.get(layer) !== "0";
  if (hash.has("walk") && W && W.orders && W.orders[+hash.get("walk")]) {
    state.walk = +hash.get("walk");
    document.querySelectorAll('input[name="walk"]')[state.walk].checked = true;
    visitInput.max = String(W.orders[state.walk].visits.length - 1);
  }
  if (hash.has("visit")) visitInput.value = hash.get("visit"), state.visit = +visitInput.value;
  resize();
  setMode(hash.get("mode") === "walk" && W && W.orders ? "walk" : "scene");
  if (hash.has("contact")) select(D.steps[state.step].contacts[+hash.get("contact")]);
  window.ccdlabPage = { state, drawScene, drawWalk, setMode, render };

  // ---- self-test (`#selftest`, tests/teaching/): what the headless test reads back -----------------------------
  function inkIn(x0, y0, x1, y1) {  // fraction of non-background pixels in a region of the canvas (fractions)
    const gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const px = new Uint8Array(4 * w * h);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let ink = 0, n = 0;
    for (let y = Math.floor(y0 * h); y < Math.floor(y1 * h); ++y)
      for (let x = Math.floor(x0 * w); x < Math.floor(x1 * w); ++x, ++n) {
        const i = 4 * ((h - 1 - y) * w + x);
        if (px[i] < 245 || px[i + 1] < 245 || px[i + 2] < 245) ++ink;
      }
    return { ink: ink / Math.max(n, 1), pixels: px };
  }
  if (location.hash.includes("selftest")) {
    const out = { steps, triangles: nfaces, csp_violations: cspViolations };
    out.resources = performance.getEntriesByType("resource").map((e) => e.name);
    render();
    const first = inkIn(0.25, 0.25, 0.75, 0.75);
    out.centre_ink = first.ink;
    const target = Math.max(0, steps - 1);
    stepInput.value = String(target);
    stepInput.dispatchEvent(new Event("input"));
    const second = inkIn(0.25, 0.25, 0.75, 0.75);
    let changed = 0;
    for (let i = 0; i < first.pixels.length; i += 4) changed += first.pixels[i] !== second.pixels[i] || first.pixels[i + 1] !== second.pixels[i + 1];
    out.changed_by_step_slider = changed / (first.pixels.length / 4);
    out.step_after = state.step;
    // Frames per second of this view (BVH, front and contacts on) while the camera turns: in headless Chromium
    // this is software rendering (SwiftShader) on the CPU, a floor for any laptop GPU.
    $("show-bvh").checked = true;
    drawScene();
    const t0 = performance.now(), n = 30;
    for (let i = 0; i < n; ++i) {
      camera.position.applyAxisAngle(new THREE.Vector3(0, 0, 1), 0.02);
      camera.lookAt(controls.target);
      render();
      renderer.getContext().finish();
    }
    out.fps_software = n / ((performance.now() - t0) / 1000);
    if (location.hash.includes("walk")) { setMode("walk"); visitInput.value = String(Math.floor(+visitInput.max / 2)); visitInput.dispatchEvent(new Event("input")); }
    $("selftest").textContent = JSON.stringify(out);
  }
})();
