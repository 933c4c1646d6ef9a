#include "studio/ui/view/preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string_view>

#include "viewer/state_pose_mapper.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "sim_core/scenario/part_look.h"
#include "studio/ui/view/live_rays.h"
#include "studio/ui/view/mujoco_buffer_cache.h"
#include "studio/ui/view/software_gl.h"

namespace mrsim::studio {
namespace {

constexpr int kExtraGeoms = 500;  // distance-sensor rays

// Everything mjr_makeContext uploads from a model besides fonts and
// buffers: textures, meshes, height fields, skins, the planes' grids and
// the quality of built-in shapes. Equal keys: the context can stay.
// A hash, not a copy: the sky alone is 4.7 MB.
size_t UploadKey(const mjModel* m) {
  size_t key = 0;
  auto put = [&key](const void* data, size_t bytes) {
    const size_t h = std::hash<std::string_view>()(
        std::string_view(static_cast<const char*>(data), bytes));
    key ^= h + 0x9e3779b97f4a7c15ULL + (key << 6) + (key >> 2);
  };
  put(&m->vis.quality, sizeof(m->vis.quality));
  put(&m->vis.global.offwidth, sizeof(int));
  put(&m->vis.global.offheight, sizeof(int));
  const int counts[] = {m->ntex,      m->ntexdata,    m->nmesh,
                        m->nmeshvert, m->nmeshface,   m->nmeshtexvert,
                        m->nhfield,   m->nhfielddata, m->nskin};
  put(counts, sizeof(counts));
  put(m->tex_type, sizeof(int) * m->ntex);
  put(m->tex_height, sizeof(int) * m->ntex);
  put(m->tex_width, sizeof(int) * m->ntex);
  put(m->tex_rgb, m->ntexdata);
  put(m->mesh_vert, sizeof(float) * 3 * m->nmeshvert);
  put(m->mesh_normal, sizeof(float) * 3 * m->nmeshvert);
  put(m->mesh_face, sizeof(int) * 3 * m->nmeshface);
  put(m->mesh_texcoord, sizeof(float) * 2 * m->nmeshtexvert);
  put(m->mesh_vertadr, sizeof(int) * m->nmesh);
  put(m->mesh_faceadr, sizeof(int) * m->nmesh);
  put(m->hfield_size, sizeof(mjtNum) * 4 * m->nhfield);
  put(m->hfield_nrow, sizeof(int) * m->nhfield);
  put(m->hfield_ncol, sizeof(int) * m->nhfield);
  put(m->hfield_data, sizeof(float) * m->nhfielddata);
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] == mjGEOM_PLANE) {
      put(m->geom_size + 3 * g, sizeof(mjtNum) * 3);
      put(m->geom_matid + g, sizeof(int));
    }
  }
  return key;
}

}  // namespace

Preview::Preview(int width, int height) : width_(width), height_(height) {
  InstallMujocoBufferCache();
  mjv_defaultScene(&scene_);
  mjv_defaultOption(&option_);
  mjv_defaultCamera(&camera_);
  camera_.type = mjCAMERA_FREE;
  mjr_defaultContext(&context_);
  option_.flags[mjVIS_RANGEFINDER] = 0;
}

Preview::~Preview() {
  if (context_made_) mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
}

std::string Preview::Rebuild(const Scenario& scenario) {
  std::unique_ptr<Physics> physics;
  try {
    physics = std::make_unique<Physics>(scenario);
  } catch (const std::exception& e) {
    return e.what();
  }
  const mjModel* m = physics->model();
  if (physics_ && physics_->model()->nbody != m->nbody && !camera_moved_) {
    framed_ = false;
  }
  physics_ = std::move(physics);
  data_ = physics_->mutable_data();
  ++builds_;
  dragging_ = false;  // a drag's saved poses were the old model's
  // Poses only: the preview draws the initial state, no dynamics needed.
  mj_kinematics(m, data_);
  mj_camlight(m, data_);
  geoms_ = MapGeoms(m, scenario);
  rays_ = MapRays(m, scenario);
  locks_ = MapLocks(m, scenario);
  labels_.clear();
  for (int r = 0; r < static_cast<int>(scenario.robots.size()); ++r) {
    for (int g = 0; g < m->ngeom; ++g) {
      const GeomPart& p = geoms_[g];
      if (p.part.kind == SelectionKind::kModule && p.part.robot == r &&
          (g + 1 >= m->ngeom || geoms_[g + 1].part != p.part)) {
        // One label per module, on its back frame's geom (the last one).
        labels_.emplace_back(g, std::to_string(p.part.index));
      }
    }
  }
  mjv_freeScene(&scene_);
  mjv_makeScene(m, &scene_, m->ngeom + kExtraGeoms);
  // The context holds the model's meshes and textures: made again per model.
  mjModel sized = *m;
  sized.vis.global.offwidth = std::max(width_, 16);
  sized.vis.global.offheight = std::max(height_, 16);
  sized.vis.quality.shadowsize = 2048;
  // Software OpenGL (llvmpipe, no GPU): multisampling and shadows cost
  // most of the frame, so they go (docs/studio.md).
  software_ = IsSoftwareGl();
  if (software_) sized.vis.quality.offsamples = 0;
  // Uploading textures (the 512x3072 sky) and buffers again costs more
  // than the compile on software GL: only when they changed. What the
  // context copies from the model's size goes over by hand.
  const size_t key = UploadKey(&sized);
  if (context_made_ && key == upload_key_) {
    context_.shadowClip =
        static_cast<float>(m->stat.extent * m->vis.map.shadowclip);
    context_.shadowScale = m->vis.map.shadowscale;
    context_.fogStart =
        static_cast<float>(m->stat.extent * m->vis.map.fogstart);
    context_.fogEnd = static_cast<float>(m->stat.extent * m->vis.map.fogend);
    for (int i = 0; i < 4; ++i) context_.fogRGBA[i] = m->vis.rgba.fog[i];
    context_.lineWidth = m->vis.global.linewidth;
  } else {
    if (context_made_) mjr_freeContext(&context_);
    mjr_makeContext(&sized, &context_, mjFONTSCALE_150);
    context_made_ = true;
    upload_key_ = key;
  }
  return "";
}

void Preview::FrameAll() {
  if (!physics_) return;
  const mjModel* m = physics_->model();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d hi = -lo;
  bool any = false;
  for (int b = 1; b < m->nbody; ++b) {
    const Eigen::Vector3d p(data_->xpos + 3 * b);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    any = true;
  }
  if (!any) {
    lo.setZero();
    hi.setZero();
  }
  const Eigen::Vector3d centre = (lo + hi) / 2;
  const double extent = std::max(0.3, (hi - lo).norm());
  for (int i = 0; i < 3; ++i) camera_.lookat[i] = centre[i];
  // Fit the extent across the narrower side of the view (fovy 45 deg).
  const double fit = std::tan(22.5 * M_PI / 180) * std::min(1.0, aspect_);
  camera_.distance = 0.58 * extent / fit + 0.1;
  camera_.azimuth = 100;  // the chain (along x) runs across the view
  camera_.elevation = -28;
  camera_moved_ = false;
}

void Preview::AddRays() {
  // Physics casts its own rays (no MuJoCo rangefinders in its model), so
  // the preview draws them, in the look's distance-sensor colour: when
  // editing as far as the simulator would read at the start, when live as
  // far as it measured (a hit brighter, with a dot where the ray ends).
  const Eigen::Vector3d rgb = PartLookRgb(PartLook::kDistanceSensor);
  const float rgba[4] = {static_cast<float>(rgb.x()),
                         static_cast<float>(rgb.y()),
                         static_cast<float>(rgb.z()), 0.7f};
  const float miss[4] = {rgba[0], rgba[1], rgba[2], 0.35f};
  const float hit[4] = {1.0f, 0.25f, 0.15f, 0.95f};
  auto add = [this](const float* colour, mjtGeom type, double width,
                    const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    if (scene_.ngeom >= scene_.maxgeom) return;
    mjvGeom* g = scene_.geoms + scene_.ngeom++;
    mjv_initGeom(g, type, nullptr, nullptr, nullptr, colour);
    mjv_makeConnector(g, type, width, from.x(), from.y(), from.z(), to.x(),
                      to.y(), to.z());
    g->category = mjCAT_DECOR;
  };
  std::vector<Ray> rays = live_ ? live_rays_ : std::vector<Ray>();
  for (const RaySite& ray : rays_) {
    const int robot = ray.part.robot;
    if (live_ && robot >= 0 && robot < static_cast<int>(live_robots_.size()) &&
        live_robots_[robot]) {
      continue;
    }
    // As the simulator would read it in this pose: to what it hits first.
    rays.push_back(CastSiteRay(physics_->model(), data_, ray.site, ray.length));
  }
  for (const Ray& ray : rays) {
    if (!ray.from.allFinite() || !ray.to.allFinite()) continue;
    add(ray.hit ? hit : miss, mjGEOM_CAPSULE, 0.003, ray.from, ray.to);
    if (ray.hit && scene_.ngeom < scene_.maxgeom) {
      mjvGeom* g = scene_.geoms + scene_.ngeom++;
      const mjtNum size[3] = {0.012, 0.012, 0.012};
      const mjtNum pos[3] = {ray.to.x(), ray.to.y(), ray.to.z()};
      mjv_initGeom(g, mjGEOM_SPHERE, size, pos, nullptr, hit);
      g->category = mjCAT_DECOR;
    }
  }
}

std::vector<std::pair<Selection, Eigen::Vector3d>> Preview::LockPoints() const {
  std::vector<std::pair<Selection, Eigen::Vector3d>> points;
  if (!physics_) return points;
  const int nbody = physics_->model()->nbody;
  for (const LockSite& lock : locks_) {
    if (lock.body_a >= nbody || lock.body_b >= nbody) continue;
    const Eigen::Map<const Eigen::Vector3d> a(data_->xpos + 3 * lock.body_a);
    const Eigen::Map<const Eigen::Vector3d> b(data_->xpos + 3 * lock.body_b);
    points.emplace_back(lock.part,
                        (a + b) / 2 + Eigen::Vector3d(0, 0, lock.lift));
  }
  return points;
}

void Preview::AddLocks(const Selection& selected) {
  // Locks have no body of their own: a marker on top of where the two
  // parts meet, so a lock can be seen and clicked as the Design panel
  // lists it.
  const float normal[4] = {0.85f, 0.85f, 0.9f, 0.9f};
  const float chosen[4] = {1.0f, 0.95f, 0.3f, 1.0f};
  for (const auto& [part, point] : LockPoints()) {
    if (scene_.ngeom >= scene_.maxgeom) return;
    mjvGeom* g = scene_.geoms + scene_.ngeom++;
    const bool on = part == selected;
    const mjtNum r = on ? 0.011 : 0.008;
    const mjtNum size[3] = {r, r, r};
    const mjtNum pos[3] = {point.x(), point.y(), point.z()};
    mjv_initGeom(g, mjGEOM_SPHERE, size, pos, nullptr, on ? chosen : normal);
    g->category = mjCAT_DECOR;
  }
}

void Preview::Bind(bool offscreen) {
  if (context_made_) {
    mjr_setBuffer(offscreen ? mjFB_OFFSCREEN : mjFB_WINDOW, &context_);
  }
}

void Preview::Render(const mjrRect& viewport, bool offscreen,
                     const Selection& selected) {
  if (!physics_) return;
  Bind(offscreen);
  aspect_ = static_cast<double>(viewport.width) / viewport.height;
  if (!framed_) {
    FrameAll();
    framed_ = true;
  }
  const mjModel* m = physics_->model();
  mjv_updateScene(m, data_, &option_, nullptr, &camera_, mjCAT_ALL, &scene_);
  // Colours come from the model (the MJCF look). The selection keeps its
  // colour (a brighter orange read as a yellow distance sensor) inside a
  // translucent white shell a little larger than the part.
  const int drawn = scene_.ngeom;
  for (int i = 0; i < drawn; ++i) {
    mjvGeom& g = scene_.geoms[i];
    if (g.objtype == mjOBJ_GEOM && g.objid >= 0 && g.objid < m->ngeom &&
        std::find(flagged_.begin(), flagged_.end(), m->geom_bodyid[g.objid]) !=
            flagged_.end()) {
      g.rgba[0] = 0.9f;  // overlapping at the start: red
      g.rgba[1] = g.rgba[2] = 0.1f;
    }
    if (g.objtype == mjOBJ_GEOM && g.objid >= 0 &&
        g.objid < static_cast<int>(geoms_.size()) &&
        geoms_[g.objid].part.kind != SelectionKind::kNone &&
        geoms_[g.objid].part == selected) {
      g.emission = 0.15f;
      if (scene_.ngeom < scene_.maxgeom) {
        mjvGeom& shell = scene_.geoms[scene_.ngeom++];
        shell = g;
        for (float& size : shell.size) size = size * 1.12f + 0.003f;
        shell.rgba[0] = shell.rgba[1] = shell.rgba[2] = 1.0f;
        shell.rgba[3] = 0.25f;
        shell.emission = 0.2f;
        shell.label[0] = '\0';
        shell.objtype = mjOBJ_UNKNOWN;  // not picked, not labelled
        shell.objid = -1;
        shell.segid = scene_.ngeom - 1;
      }
    }
  }
  if (software_) scene_.flags[mjRND_SHADOW] = 0;
  // The floor's reflection draws the floor twice more (stencil, blend):
  // on software GL a third of the view's time, so a drag (where the frame
  // rate is what the user feels) goes without it (docs/studio.md).
  scene_.flags[mjRND_REFLECTION] = software_ && dragging_ ? 0 : 1;
  for (int i = 0; i < scene_.ngeom; ++i) {
    mjvGeom& g = scene_.geoms[i];
    if (g.objtype != mjOBJ_GEOM) continue;
    for (const auto& [geom, text] : labels_) {
      if (g.objid == geom) {
        std::snprintf(g.label, sizeof(g.label), "%s", text.c_str());
      }
    }
  }
  AddRays();
  AddLocks(selected);
  if (software_) CoarsenInfinitePlanes(m, context_, &scene_);
  mjr_render(viewport, &scene_, &context_);
}

void Preview::ReadPixels(int width, int height,
                         std::vector<unsigned char>* rgb) {
  rgb->resize(static_cast<size_t>(width) * height * 3);
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  mjr_readPixels(rgb->data(), nullptr, {0, 0, width, height}, &context_);
}

void Preview::Orbit(double dx, double dy) {
  camera_moved_ = true;
  if (physics_) {
    mjv_moveCamera(physics_->model(), mjMOUSE_ROTATE_V, dx, dy, &scene_,
                   &camera_);
  }
}

void Preview::Pan(double dx, double dy) {
  camera_moved_ = true;
  if (physics_) {
    mjv_moveCamera(physics_->model(), mjMOUSE_MOVE_V, dx, dy, &scene_,
                   &camera_);
  }
}

void Preview::Zoom(double amount) {
  camera_moved_ = true;
  if (physics_) {
    mjv_moveCamera(physics_->model(), mjMOUSE_ZOOM, 0, amount, &scene_,
                   &camera_);
  }
}

Selection Preview::Pick(const mjrRect& viewport, double x, double y) const {
  if (!physics_) return {};
  // A lock's marker first: it sits on the parts it joins, which would
  // otherwise take the click. Within a few pixels of its centre.
  constexpr double kLockPixels = 8;
  Selection lock;
  double best = kLockPixels * kLockPixels;
  for (const auto& [part, point] : LockPoints()) {
    double sx = 0, sy = 0;
    // Window height = the viewport's top, so y comes out from its top.
    if (!ScreenPoint(viewport, viewport.bottom + viewport.height, point, &sx,
                     &sy)) {
      continue;
    }
    const double dx = sx - viewport.left - x, dy = sy - y;
    if (dx * dx + dy * dy < best) {
      best = dx * dx + dy * dy;
      lock = part;
    }
  }
  if (lock.kind != SelectionKind::kNone) return lock;
  mjtNum point[3];
  int geom = -1;
  int skin = -1;
  const mjtNum aspect = static_cast<mjtNum>(viewport.width) / viewport.height;
  mjv_select(physics_->model(), data_, &option_, aspect, x / viewport.width,
             (viewport.height - y) / viewport.height, &scene_, point, &geom,
             &skin);
  if (geom < 0 || geom >= static_cast<int>(geoms_.size())) return {};
  return geoms_[geom].part;
}

bool Preview::ScreenPoint(const mjrRect& viewport, int window_height,
                          const Eigen::Vector3d& world, double* x,
                          double* y) const {
  if (!physics_ || scene_.ngeom == 0) return false;
  // The scene's camera as mjr_render used it (average of the two eyes).
  const mjvGLCamera& c = scene_.camera[0];
  const Eigen::Vector3d pos(c.pos[0], c.pos[1], c.pos[2]);
  const Eigen::Vector3d forward(c.forward[0], c.forward[1], c.forward[2]);
  const Eigen::Vector3d up(c.up[0], c.up[1], c.up[2]);
  const Eigen::Vector3d right = forward.cross(up);
  const double half_h = (c.frustum_top - c.frustum_bottom) / 2;
  const double centre_y = (c.frustum_top + c.frustum_bottom) / 2;
  const double half_w =
      half_h * static_cast<double>(viewport.width) / viewport.height;
  const Eigen::Vector3d v = world - pos;
  const double z = v.dot(forward);
  if (z <= c.frustum_near) return false;
  const double sx = v.dot(right) * c.frustum_near / z;
  const double sy = v.dot(up) * c.frustum_near / z;
  const double nx = (sx - c.frustum_center) / half_w;
  const double ny = (sy - centre_y) / half_h;
  *x = viewport.left + (nx + 1) / 2 * viewport.width;
  *y = window_height - (viewport.bottom + (ny + 1) / 2 * viewport.height);
  return true;
}

bool Preview::GroundPoint(const mjrRect& viewport, int window_height, double x,
                          double y, double z, Eigen::Vector3d* point) const {
  if (!physics_ || scene_.ngeom == 0) return false;
  const mjvGLCamera& c = scene_.camera[0];
  const Eigen::Vector3d pos(c.pos[0], c.pos[1], c.pos[2]);
  const Eigen::Vector3d forward(c.forward[0], c.forward[1], c.forward[2]);
  const Eigen::Vector3d up(c.up[0], c.up[1], c.up[2]);
  const Eigen::Vector3d right = forward.cross(up);
  const double half_h = (c.frustum_top - c.frustum_bottom) / 2;
  const double centre_y = (c.frustum_top + c.frustum_bottom) / 2;
  const double half_w =
      half_h * static_cast<double>(viewport.width) / viewport.height;
  const double nx = (x - viewport.left) / viewport.width * 2 - 1;
  const double ny =
      (window_height - y - viewport.bottom) / viewport.height * 2 - 1;
  const Eigen::Vector3d dir = forward * c.frustum_near +
                              right * (nx * half_w + c.frustum_center) +
                              up * (ny * half_h + centre_y);
  if (std::abs(dir.z()) < 1e-12) return false;
  const double t = (z - pos.z()) / dir.z();
  if (t <= 0) return false;
  *point = pos + t * dir;
  return true;
}

std::vector<PartMarker> Preview::Markers(const mjrRect& viewport,
                                         int window_height) const {
  std::vector<PartMarker> markers;
  if (!physics_ || scene_.ngeom == 0) return markers;
  const mjModel* m = physics_->model();
  for (int g = 0; g < m->ngeom; ++g) {
    const GeomPart& part = geoms_[g];
    if (part.look != Look::kPitchModule && part.look != Look::kYawModule &&
        part.look != Look::kSensorModule) {
      continue;
    }
    double x = 0, y = 0;
    if (ScreenPoint(viewport, window_height,
                    Eigen::Vector3d(data_->geom_xpos + 3 * g), &x, &y)) {
      markers.push_back({part.part, x, y});
    }
  }
  for (const auto& [part, point] : LockPoints()) {
    double x = 0, y = 0;
    if (ScreenPoint(viewport, window_height, point, &x, &y)) {
      markers.push_back({part, x, y});
    }
  }
  return markers;
}

void Preview::ShowDrag(const Selection& what, const Eigen::Isometry3d& t,
                       const std::vector<Selection>& loose_group) {
  if (!physics_ || live_) return;
  const mjModel* m = physics_->model();
  // From the design's pose each time, kept at the drag's start (cheaper
  // than the kinematics again every frame).
  if (!dragging_) {
    drag_xpos_.assign(data_->geom_xpos, data_->geom_xpos + 3 * m->ngeom);
    drag_xmat_.assign(data_->geom_xmat, data_->geom_xmat + 9 * m->ngeom);
  }
  const bool robot = what.kind == SelectionKind::kRobot ||
                     what.kind == SelectionKind::kModule ||
                     what.kind == SelectionKind::kSensorModule;
  const Eigen::Matrix3d r = t.linear();
  for (int g = 0; g < m->ngeom && g < static_cast<int>(geoms_.size()); ++g) {
    const Selection& p = geoms_[g].part;
    const bool loose = std::find(loose_group.begin(), loose_group.end(), p) !=
                       loose_group.end();
    const bool moves =
        robot ? (p.kind == SelectionKind::kModule ||
                 p.kind == SelectionKind::kSensorModule ||
                 p.kind == SelectionKind::kRobot) &&
                    p.robot == what.robot
              : loose || (what.kind == SelectionKind::kSceneObject &&
                          p.kind == SelectionKind::kSceneObject &&
                          p.index == what.index);
    if (!moves) continue;
    using RowMajor = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
    Eigen::Map<Eigen::Vector3d>(data_->geom_xpos + 3 * g) =
        t * Eigen::Vector3d(drag_xpos_.data() + 3 * g);
    // geom_xmat is row-major.
    Eigen::Map<RowMajor>(data_->geom_xmat + 9 * g) =
        r * Eigen::Map<const RowMajor>(drag_xmat_.data() + 9 * g);
  }
  dragging_ = true;
}

void Preview::EndDrag() {
  if (!dragging_) return;
  dragging_ = false;
  if (physics_ && !live_ &&
      drag_xpos_.size() == 3 * static_cast<size_t>(physics_->model()->ngeom)) {
    std::copy(drag_xpos_.begin(), drag_xpos_.end(), data_->geom_xpos);
    std::copy(drag_xmat_.begin(), drag_xmat_.end(), data_->geom_xmat);
  }
}

void Preview::ShowStates(const Scenario& scenario,
                         const std::map<std::string, RobotState>& states,
                         const std::vector<SceneObjectState>* scene) {
  if (!physics_) return;
  try {
    if (!mapper_) {
      mapper_ = std::make_unique<StatePoseMapper>(physics_->model(), scenario);
    }
  } catch (const std::exception&) {
    return;  // a design the mapper cannot follow: the design pose stays
  }
  std::vector<const RobotState*> list(mapper_->robot_count(), nullptr);
  for (int r = 0; r < mapper_->robot_count(); ++r) {
    const auto it = states.find(mapper_->robot_name(r));
    if (it != states.end() && mapper_->Check(r, it->second).empty()) {
      list[r] = &it->second;
    }
  }
  if (scene != nullptr && !mapper_->CheckScene(*scene).empty()) scene = nullptr;
  mapper_->Apply(list, data_, scene);
  live_rays_ = MeasuredRays(*mapper_, list, data_);
  live_robots_.assign(list.size(), false);
  for (size_t r = 0; r < list.size(); ++r) live_robots_[r] = list[r] != nullptr;
  live_ = true;

  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int n = 0;
  for (const RobotState* s : list) {
    if (s != nullptr) {
      centre += s->com;
      ++n;
    }
  }
  if (n == 0 || !tracking_) {
    tracked_ = false;
    return;
  }
  centre /= n;
  if (tracked_) {
    // Horizontal only: a robot that rears up does not tilt the view.
    for (int k = 0; k < 2; ++k) {
      camera_.lookat[k] += centre[k] - tracked_centre_[k];
    }
  }
  tracked_centre_ = centre;
  tracked_ = true;
}

void Preview::ShowDesign() {
  mapper_.reset();
  tracked_ = false;
  live_rays_.clear();
  live_robots_.clear();
  if (live_ && physics_) {
    mj_kinematics(physics_->model(), data_);
    mj_camlight(physics_->model(), data_);
  }
  live_ = false;
}

}  // namespace mrsim::studio
