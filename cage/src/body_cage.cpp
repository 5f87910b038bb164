#include "pixelcloth/cage/body_cage.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>

#include "pixelcloth/core/error.h"

namespace pixelcloth::cage {

namespace {

using Vec = Eigen::Vector3d;

/// A plane that a curve should stay close to.
struct Plane {
  Vec point;
  Vec normal;  // unit
  double distance(const Vec& p) const { return std::abs((p - point).dot(normal)); }
};

class SurfaceWalker {
 public:
  SurfaceWalker(const core::Mesh& mesh, double tolerance) : V_(mesh.V), tolerance_(tolerance) {
    neighbours_.resize(mesh.numVertices());
    for (int f = 0; f < mesh.numFaces(); ++f)
      for (int k = 0; k < 3; ++k) {
        int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        neighbours_[a].push_back(b);
        neighbours_[b].push_back(a);
      }
    double total = 0;
    int count = 0;
    for (int v = 0; v < mesh.numVertices(); ++v) {
      auto& n = neighbours_[v];
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
      for (int w : n) total += (position(v) - position(w)).norm(), ++count;
    }
    // Landmark slabs must hold a ring of vertices whatever the mesh resolution.
    slab_ = std::max(0.006, 0.75 * total / std::max(count, 1));
  }

  double slab() const { return slab_; }

  Vec position(int v) const { return V_.row(v).transpose(); }

  /// The vertex seen from `centre` furthest in direction `direction`, among vertices within `slab` of the plane
  /// through `centre` with normal `axis` and accepted by `keep`.
  int landmark(const Vec& centre, const Vec& axis, const Vec& direction, double slab,
               const std::function<bool(const Vec&)>& keep, const std::string& what) const {
    int best = -1;
    double bestScore = -std::numeric_limits<double>::infinity();
    for (int v = 0; v < V_.rows(); ++v) {
      Vec d = position(v) - centre;
      double along = d.dot(axis);
      if (std::abs(along) > slab || !keep(position(v))) continue;
      Vec radial = d - along * axis;
      double r = radial.norm();
      if (r < 1e-9) continue;
      // Mostly the angle to `direction`, then the distance (outermost surface point on that ray).
      double score = radial.dot(direction) / r + 1e-3 * r;
      if (score > bestScore) {
        bestScore = score;
        best = v;
      }
    }
    PIXELCLOTH_CHECK(best >= 0, "body cage: cannot place the " << what << " on the body surface");
    return best;
  }

  /// Shortest path along mesh edges from a to b (both included), edges weighted by length times
  /// 1 + (distance to the plane / tolerance)^2; vertices in `avoid` are not entered (except b).
  std::vector<int> path(int a, int b, const Plane& plane, const std::set<int>& avoid) const {
    const int n = static_cast<int>(V_.rows());
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    std::vector<int> previous(n, -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    dist[a] = 0;
    queue.push({0, a});
    while (!queue.empty()) {
      auto [d, v] = queue.top();
      queue.pop();
      if (d > dist[v]) continue;
      if (v == b) break;
      for (int w : neighbours_[v]) {
        if (w != b && avoid.count(w)) continue;
        Vec mid = 0.5 * (position(v) + position(w));
        double off = plane.distance(mid) / tolerance_;
        double cost = d + (position(w) - position(v)).norm() * (1.0 + off * off);
        if (cost < dist[w]) {
          dist[w] = cost;
          previous[w] = v;
          queue.push({cost, w});
        }
      }
    }
    PIXELCLOTH_CHECK(previous[b] >= 0 || a == b,
                     "body cage: no path along the surface between vertices " << a << " and " << b);
    std::vector<int> chain;
    for (int v = b; v != -1; v = previous[v]) chain.push_back(v);
    std::reverse(chain.begin(), chain.end());
    return chain;
  }

 private:
  const Eigen::MatrixX3d& V_;
  double tolerance_;
  double slab_ = 0.006;
  std::vector<std::vector<int>> neighbours_;
};

/// Joins paths through consecutive waypoints into one chain (closed: back to the first waypoint).
/// The chain never visits a vertex twice; other curves are ignored (they meet it at shared waypoints).
std::vector<int> chainThrough(const SurfaceWalker& walker, const std::vector<int>& waypoints, const Plane& plane,
                              bool closed) {
  std::vector<int> chain = {waypoints.front()};
  std::set<int> used = {waypoints.front()};
  for (int w : waypoints) used.insert(w);
  size_t legs = closed ? waypoints.size() : waypoints.size() - 1;
  for (size_t i = 0; i < legs; ++i) {
    int from = waypoints[i], to = waypoints[(i + 1) % waypoints.size()];
    std::set<int> avoid = used;
    avoid.erase(from);
    if (closed && i + 1 == legs) avoid.erase(to);
    std::vector<int> leg = walker.path(from, to, plane, avoid);
    for (size_t k = 1; k < leg.size(); ++k) {
      if (closed && i + 1 == legs && k + 1 == leg.size()) break;  // do not repeat the first vertex
      chain.push_back(leg[k]);
      used.insert(leg[k]);
    }
  }
  return chain;
}

}  // namespace

void BodyCageOptions::validate() const {
  PIXELCLOTH_CHECK(planeTolerance > 0, "body cage: plane tolerance must be positive");
  PIXELCLOTH_CHECK(bicepFromShoulder > armholeOutsideArm && sleeveHemFromShoulder > bicepFromShoulder,
                   "body cage: expected armhole < bicep < sleeve hem along the arm");
}

Cage bodyCage(const body::Body& body, const BodyCageOptions& options) {
  options.validate();
  const body::Skeleton& s = body.skeleton;
  SurfaceWalker walker(body.mesh, options.planeTolerance);
  auto joint = [&](const std::string& name) -> Vec { return s.positions.row(s.index(name)).transpose(); };
  const Vec up = Vec::UnitY(), front = Vec::UnitZ(), left = Vec::UnitX();

  // Torso loops: a horizontal slab at each height, arms excluded by staying between the shoulders.
  double shoulderX = std::min(joint("l_arm").x(), -joint("r_arm").x());
  auto onTorso = [&](const Vec& p) { return std::abs(p.x()) < shoulderX + 0.12; };
  struct Loop {
    std::string name;
    double height;
  };
  const double chestY = joint("spine1").y() - options.chestBelowSpine1;
  const double waistY = 0.5 * (joint("lower_back").y() + joint("spine").y());
  const double hemY = joint("root").y() - options.hemBelowRoot;
  const Vec torsoCentre = 0.5 * (joint("spine1") + joint("lower_back"));

  Cage cage;
  std::map<int, std::vector<std::string>> waypointCurves;  // landmark vertex -> curves planned through it
  auto torsoPoint = [&](double y, const Vec& direction, const std::string& what) {
    Vec centre(torsoCentre.x(), y, torsoCentre.z());
    return walker.landmark(centre, up, direction, walker.slab(), onTorso, what);
  };
  struct TorsoLoop {
    int front, left, back, right;
  };
  auto torsoLoop = [&](const std::string& name, double y) {
    TorsoLoop l{torsoPoint(y, front, name + " front"), torsoPoint(y, left, name + " left side"),
                torsoPoint(y, -front, name + " back"), torsoPoint(y, -left, name + " right side")};
    return l;
  };
  TorsoLoop chest = torsoLoop("chest", chestY), waist = torsoLoop("waist", waistY), hem = torsoLoop("hem", hemY);

  // Neck: lower in front than at the back, like a neckline.
  const Vec neck = joint("neck");
  auto onNeck = [&](const Vec& p) { return std::abs(p.x()) < 0.1 && p.y() > neck.y() - 0.08; };
  int neckFront =
      walker.landmark(Vec(neck.x(), neck.y() - 0.04, neck.z()), up, front, walker.slab(), onNeck, "neck front");
  int neckBack = walker.landmark(Vec(neck.x(), neck.y(), neck.z()), up, -front, walker.slab(), onNeck, "neck back");
  int neckLeft =
      walker.landmark(Vec(neck.x(), neck.y() + 0.005, neck.z()), up, left, walker.slab(), onNeck, "neck left");
  int neckRight =
      walker.landmark(Vec(neck.x(), neck.y() + 0.005, neck.z()), up, -left, walker.slab(), onNeck, "neck right");

  // Arms: loops across the arm at distances along the shoulder-to-elbow direction.
  struct Ring {
    int top, bottom, front, back;  ///< landmarks around the arm
  };
  struct ArmLoops {
    Ring armhole, bicep, hem;  ///< the armhole's top is the shoulder point, its bottom the armpit
    Vec axis, shoulder;
  };
  auto armLoops = [&](const std::string& side) {
    ArmLoops a;
    a.shoulder = joint(side + "_arm");
    a.axis = (joint(side + "_forearm") - a.shoulder).normalized();
    auto onArmSide = [&](const Vec& p) {
      return (p - a.shoulder).dot(a.axis) > -0.05 && std::abs(p.y() - a.shoulder.y()) < 0.16;
    };
    auto at = [&](double distance, const Vec& direction, const std::string& what) {
      return walker.landmark(a.shoulder + distance * a.axis, a.axis, direction, walker.slab(), onArmSide,
                             side + " " + what);
    };
    // Braced initialisation runs left to right: top, bottom, front, back.
    auto ring = [&](double distance, const std::string& top, const std::string& bottom, const std::string& what) {
      return Ring{at(distance, up, top), at(distance, -up, bottom), at(distance, front, what + " front"),
                  at(distance, -front, what + " back")};
    };
    a.armhole = ring(options.armholeOutsideArm, "shoulder point", "armpit", "armhole");
    a.bicep = ring(options.bicepFromShoulder, "bicep top", "bicep bottom", "bicep");
    a.hem = ring(options.sleeveHemFromShoulder, "sleeve hem top", "sleeve hem bottom", "sleeve hem");
    return a;
  };
  ArmLoops leftArm = armLoops("l"), rightArm = armLoops("r");

  auto add = [&](const std::string& name, CurveKind kind, bool closed, const std::vector<int>& waypoints,
                 const Plane& plane) {
    std::vector<int> chain;
    try {
      chain = chainThrough(walker, waypoints, plane, closed);
    } catch (const core::InputError& e) {
      PIXELCLOTH_FAIL("body cage: curve '" << name << "': " << e.what());
    }
    for (int v : waypoints) waypointCurves[v].push_back(name);
    cage.curves.push_back({name, kind, closed, chain});
  };
  auto horizontal = [&](double y) { return Plane{Vec(0, y, 0), up}; };
  const Plane sagittal{torsoCentre, left};
  const Plane coronal{torsoCentre, front};

  // Loops first (their landmarks are the junctions), then the lines between them.
  add("chest", CurveKind::Loop, true, {chest.front, chest.left, chest.back, chest.right}, horizontal(chestY));
  add("waist", CurveKind::Loop, true, {waist.front, waist.left, waist.back, waist.right}, horizontal(waistY));
  add("hem", CurveKind::Opening, true, {hem.front, hem.left, hem.back, hem.right}, horizontal(hemY));
  Plane neckPlane{walker.position(neckFront), (walker.position(neckBack) - walker.position(neckFront))
                                                  .cross(walker.position(neckLeft) - walker.position(neckRight))
                                                  .normalized()};
  add("neckline", CurveKind::Opening, true, {neckFront, neckLeft, neckBack, neckRight}, neckPlane);
  add("centre_front", CurveKind::CentreLine, false, {neckFront, chest.front, waist.front, hem.front}, sagittal);
  add("centre_back", CurveKind::CentreLine, false, {neckBack, chest.back, waist.back, hem.back}, sagittal);
  for (const auto& [side, arm, torsoSide] :
       {std::tuple<std::string, const ArmLoops*, int>{"left", &leftArm, 0}, {"right", &rightArm, 1}}) {
    const ArmLoops& a = *arm;
    int chestSide = torsoSide == 0 ? chest.left : chest.right;
    int waistSide = torsoSide == 0 ? waist.left : waist.right;
    int hemSide = torsoSide == 0 ? hem.left : hem.right;
    int neckSide = torsoSide == 0 ? neckLeft : neckRight;
    Plane across{a.shoulder + options.armholeOutsideArm * a.axis, a.axis};
    add("armhole_front_" + side, CurveKind::Seam, false, {a.armhole.top, a.armhole.front, a.armhole.bottom}, across);
    add("armhole_back_" + side, CurveKind::Seam, false, {a.armhole.top, a.armhole.back, a.armhole.bottom}, across);
    Plane bicepPlane{a.shoulder + options.bicepFromShoulder * a.axis, a.axis};
    add("bicep_" + side, CurveKind::Loop, true, {a.bicep.top, a.bicep.front, a.bicep.bottom, a.bicep.back}, bicepPlane);
    Plane hemPlane{a.shoulder + options.sleeveHemFromShoulder * a.axis, a.axis};
    add("sleeve_hem_" + side, CurveKind::Opening, true, {a.hem.top, a.hem.front, a.hem.bottom, a.hem.back}, hemPlane);
    Plane armTop{a.shoulder, front};
    add("shoulder_" + side, CurveKind::Seam, false, {neckSide, a.armhole.top}, armTop);
    add("sleeve_top_" + side, CurveKind::Seam, false, {a.armhole.top, a.bicep.top, a.hem.top}, armTop);
    add("underarm_" + side, CurveKind::Seam, false, {a.armhole.bottom, a.bicep.bottom, a.hem.bottom}, armTop);
    add("side_" + side, CurveKind::Seam, false, {a.armhole.bottom, chestSide, waistSide, hemSide}, coronal);
  }
  // Junctions are the landmarks that several curves were planned through (curves computed independently may also
  // touch elsewhere near a junction; those contacts are not nodes). Named like junctions(): every curve, sorted.
  for (auto& [vertex, names] : waypointCurves) {
    if (names.size() < 2) continue;
    std::sort(names.begin(), names.end());
    std::string name;
    for (const std::string& n : names) name += (name.empty() ? "" : "/") + n;
    cage.nodes.push_back({name, vertex});
  }
  cage.validate(body.mesh.F, body.mesh.numVertices(), "body cage");
  return cage;
}

}  // namespace pixelcloth::cage
