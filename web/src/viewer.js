import {
  Box3,
  Color,
  DirectionalLight,
  GridHelper,
  HemisphereLight,
  PerspectiveCamera,
  Scene,
  Sphere,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const BACKGROUND = new Color(0x24272e);
// Seen from the right front and a little above: shows the silhouette and the depth of a pose.
const VIEW_DIRECTION = new Vector3(1.5, 0.5, 1).normalize();

// The three.js side of the page: renderer, camera, lights and the model currently shown. Draws only
// when asked (see main.js), so an idle page costs nothing.
export class Viewer {
  constructor(canvas, onChange) {
    this.renderer = new WebGLRenderer({ canvas, antialias: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.scene = new Scene();
    this.scene.background = BACKGROUND;
    this.scene.add(new HemisphereLight(0xdfe8ff, 0x3a3228, 1.6));
    this.light = new DirectionalLight(0xffffff, 2.2);
    this.scene.add(this.light, this.light.target);
    this.camera = new PerspectiveCamera(35, 1, 0.01, 100);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', onChange);
    // Until the user moves the camera, a resized window is framed again.
    this.controls.addEventListener('start', () => {
      this.userMoved = true;
    });
    this.model = null;
    this.grid = null;
    this.userMoved = false;

    // The canvas fills whatever room the layout gives it.
    new ResizeObserver(() => {
      this.resize();
      if (this.model !== null && !this.userMoved) this.frame();
      onChange();
    }).observe(canvas.parentElement);
    this.resize();
  }

  resize() {
    const { clientWidth: width, clientHeight: height } = this.renderer.domElement.parentElement;
    if (width === 0 || height === 0) return;
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
  }

  // Morph targets three.js can draw on one mesh: it keeps them as the layers of one array texture.
  maxMorphTargets() {
    const gl = this.renderer.getContext();
    return gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS);
  }

  // Replaces the shown model (a glTF scene) and frames the camera on `positions` (flat xyz, the
  // poses it will take).
  show(root, positions) {
    this.clear();
    this.model = root;
    // Morph targets and skinning move vertices outside the bind pose's bounds, which three would
    // otherwise use to cull the mesh.
    root.traverse((object) => {
      if (object.isMesh) object.frustumCulled = false;
    });
    this.scene.add(root);
    this.positions = positions;
    this.userMoved = false;
    this.frame();
  }

  clear() {
    if (this.model === null) return;
    this.scene.remove(this.model);
    this.model.traverse((object) => {
      if (!object.isMesh) return;
      object.geometry.dispose();
      for (const material of [object.material].flat()) material.dispose();
      object.skeleton?.dispose(); // its bone texture
    });
    this.model = null;
  }

  // Points the camera at the model's poses, with a ground grid under them, and scales the near/far
  // planes and the light to the model's size (odeskin keeps the input's units).
  frame() {
    const positions = this.positions;
    const box = new Box3().setFromArray(positions);
    if (box.isEmpty()) box.setFromCenterAndSize(new Vector3(), new Vector3(1, 1, 1));
    const sphere = box.getBoundingSphere(new Sphere());
    const radius = Math.max(sphere.radius, 1e-6);
    const distance = this.fittingDistance(positions, sphere.center) || 3 * radius;
    this.camera.position.copy(sphere.center).addScaledVector(VIEW_DIRECTION, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.light.position.copy(sphere.center).add(new Vector3(0.5, 1, 0.8).multiplyScalar(distance));
    this.light.target.position.copy(sphere.center);

    const size = 4 * radius;
    if (this.grid !== null) {
      this.scene.remove(this.grid);
      this.grid.dispose();
    }
    this.grid = new GridHelper(size, 16, 0x5a606c, 0x3a3f48);
    this.grid.position.set(sphere.center.x, box.min.y, sphere.center.z);
    this.scene.add(this.grid);
  }

  // How far from `center` along VIEW_DIRECTION the camera must stand to see every vertex with a
  // margin (for the poses that move further out). Tighter than fitting the bounding sphere or box,
  // which leave long shapes (a horse, an arm) small in the middle of the view.
  fittingDistance(positions, center) {
    const forward = VIEW_DIRECTION.clone().negate();
    const right = new Vector3().crossVectors(forward, this.camera.up).normalize();
    const up = new Vector3().crossVectors(right, forward);
    const tanVertical = Math.tan((this.camera.fov * Math.PI) / 360);
    const tanHorizontal = tanVertical * this.camera.aspect;
    const margin = 1.1;
    const offset = new Vector3();
    let distance = 0;
    for (let i = 0; i < positions.length; i += 3) {
      offset.fromArray(positions, i).sub(center);
      // A vertex nearer the camera needs the camera that much further away.
      const toward = offset.dot(VIEW_DIRECTION);
      distance = Math.max(
        distance,
        toward + (margin * Math.abs(offset.dot(right))) / tanHorizontal,
        toward + (margin * Math.abs(offset.dot(up))) / tanVertical,
      );
    }
    return distance;
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }
}
