#include "sim/box2d_world.hpp"

#include <box2d/box2d.h>

#include <cmath>

namespace slambox {

namespace {
enum FixtureKind : uintptr_t { kRobot = 1, kWall = 2, kMover = 3 };

b2Vec2 ToB2(const Eigen::Vector2d& p) { return b2Vec2(static_cast<float>(p.x()), static_cast<float>(p.y())); }

class ContactCounter : public b2ContactListener {
 public:
  ContactCounts counts;
  void BeginContact(b2Contact* contact) override {
    const uintptr_t a = contact->GetFixtureA()->GetUserData().pointer;
    const uintptr_t b = contact->GetFixtureB()->GetUserData().pointer;
    if (a != kRobot && b != kRobot) return;
    const uintptr_t other = a == kRobot ? b : a;
    if (other == kWall) ++counts.robot_wall;
    if (other == kMover) ++counts.robot_mover;
  }
};

class ClosestHit : public b2RayCastCallback {
 public:
  float fraction = 2.0f;
  float ReportFixture(b2Fixture* fixture, const b2Vec2&, const b2Vec2&, float f) override {
    if (fixture->GetUserData().pointer == kRobot) return -1.0f;  // the robot's own disc
    fraction = f;
    return f;  // clip the ray: later reports are closer
  }
};
}  // namespace

Eigen::Vector2d MoverPositionAt(const MoverSpec& mover, double t_s) {
  const auto& path = mover.path;
  if (path.empty()) return Eigen::Vector2d::Zero();
  double length = 0.0;
  for (size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  if (length <= 0.0 || mover.speed_mps <= 0.0) return path.front();
  double s = mover.speed_mps * t_s;  // arc length travelled
  if (mover.loop) {
    s = std::fmod(s, 2.0 * length);  // out and back
    if (s > length) s = 2.0 * length - s;
  } else {
    s = std::min(s, length);
  }
  for (size_t i = 1; i < path.size(); ++i) {
    const double seg = (path[i] - path[i - 1]).norm();
    if (s <= seg || i + 1 == path.size()) return seg > 0.0 ? path[i - 1] + std::min(s / seg, 1.0) * (path[i] - path[i - 1]) : path[i];
    s -= seg;
  }
  return path.back();
}

struct PhysicsWorld::Impl {
  b2World world{b2Vec2(0.0f, 0.0f)};
  ContactCounter counter;
  b2Body* robot = nullptr;
  std::vector<b2Body*> mover_bodies;
  std::vector<MoverSpec> mover_specs;
};

PhysicsWorld::PhysicsWorld(const Scenario& scenario, const World& world) : impl_(std::make_unique<Impl>()) {
  b2World& w = impl_->world;
  w.SetContactListener(&impl_->counter);
  b2BodyDef static_def;
  b2Body* statics = w.CreateBody(&static_def);
  b2FixtureDef fd;
  fd.userData.pointer = kWall;
  for (const Segment& s : world.wall_segments) {
    if ((s.b - s.a).norm() < 1e-6) continue;  // Box2D rejects degenerate edges; they are never hit
    b2EdgeShape edge;
    edge.SetTwoSided(ToB2(s.a), ToB2(s.b));
    fd.shape = &edge;
    statics->CreateFixture(&fd);
  }
  auto add_circle = [&](const Eigen::Vector2d& c, double r) {
    b2CircleShape circle;
    circle.m_p = ToB2(c);
    circle.m_radius = static_cast<float>(r);
    fd.shape = &circle;
    statics->CreateFixture(&fd);
  };
  for (const Circle& c : world.wall_circles) add_circle(c.center, c.radius_m);
  for (const TrueLandmark& lm : world.landmarks) add_circle(lm.position, lm.radius_m);

  for (const MoverSpec& m : scenario.movers) {
    b2BodyDef def;
    def.type = b2_kinematicBody;
    def.position = ToB2(MoverPositionAt(m, 0.0));
    b2Body* body = w.CreateBody(&def);
    b2FixtureDef mfd;
    mfd.userData.pointer = kMover;
    b2PolygonShape box;
    b2CircleShape circle;
    if (m.is_box) {
      box.SetAsBox(static_cast<float>(m.size.x() / 2), static_cast<float>(m.size.y() / 2));
      mfd.shape = &box;
    } else {
      circle.m_radius = static_cast<float>(m.radius_m);
      mfd.shape = &circle;
    }
    body->CreateFixture(&mfd);
    impl_->mover_bodies.push_back(body);
    impl_->mover_specs.push_back(m);
  }

  b2BodyDef robot_def;
  robot_def.type = b2_dynamicBody;
  robot_def.allowSleep = false;
  robot_def.position.Set(static_cast<float>(scenario.robot.start.x), static_cast<float>(scenario.robot.start.y));
  robot_def.angle = static_cast<float>(scenario.robot.start.theta_deg * M_PI / 180.0);
  impl_->robot = w.CreateBody(&robot_def);
  b2CircleShape disc;
  disc.m_radius = static_cast<float>(scenario.robot.radius_m);
  b2FixtureDef rfd;
  rfd.shape = &disc;
  rfd.density = 1.0f;
  rfd.friction = 0.0f;
  rfd.userData.pointer = kRobot;
  impl_->robot->CreateFixture(&rfd);
}

PhysicsWorld::~PhysicsWorld() = default;

void PhysicsWorld::SetRobotVelocity(double v_mps, double w_rps) {
  const float a = impl_->robot->GetAngle();
  impl_->robot->SetLinearVelocity(b2Vec2(static_cast<float>(v_mps) * std::cos(a), static_cast<float>(v_mps) * std::sin(a)));
  impl_->robot->SetAngularVelocity(static_cast<float>(w_rps));
}

void PhysicsWorld::Step(double dt_s, double t_next_s) {
  for (size_t i = 0; i < impl_->mover_bodies.size(); ++i) {
    b2Body* body = impl_->mover_bodies[i];
    const b2Vec2 target = ToB2(MoverPositionAt(impl_->mover_specs[i], t_next_s));
    const b2Vec2 v = (1.0f / static_cast<float>(dt_s)) * (target - body->GetPosition());
    body->SetLinearVelocity(v);
  }
  // Velocity and position iterations as recommended by the Box2D manual (8, 3).
  impl_->world.Step(static_cast<float>(dt_s), 8, 3);
}

SE2 PhysicsWorld::RobotPose() const {
  const b2Vec2 p = impl_->robot->GetPosition();
  return SE2(p.x, p.y, impl_->robot->GetAngle());
}

double PhysicsWorld::RobotYawRate() const { return impl_->robot->GetAngularVelocity(); }

void PhysicsWorld::TeleportRobot(const SE2& T) {
  impl_->robot->SetTransform(b2Vec2(static_cast<float>(T.x), static_cast<float>(T.y)), static_cast<float>(T.theta));
  impl_->robot->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
  impl_->robot->SetAngularVelocity(0.0f);
}

std::vector<MoverShape> PhysicsWorld::Movers() const {
  std::vector<MoverShape> shapes;
  shapes.reserve(impl_->mover_bodies.size());
  for (size_t i = 0; i < impl_->mover_bodies.size(); ++i) {
    const b2Body* body = impl_->mover_bodies[i];
    const MoverSpec& m = impl_->mover_specs[i];
    MoverShape s;
    s.T_world_mover = SE2(body->GetPosition().x, body->GetPosition().y, body->GetAngle());
    s.is_box = m.is_box;
    if (m.is_box) s.box_size_m = m.size;
    else s.radius_m = m.radius_m;
    shapes.push_back(s);
  }
  return shapes;
}

ContactCounts PhysicsWorld::contacts() const { return impl_->counter.counts; }

double PhysicsWorld::RayCastBox2D(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m) const {
  ClosestHit hit;
  const b2Vec2 p1 = ToB2(o), p2 = ToB2(o + max_range_m * d);
  impl_->world.RayCast(&hit, p1, p2);
  if (hit.fraction > 1.0f) return kNoHit;
  return static_cast<double>(hit.fraction) * (p2 - p1).Length();
}

}  // namespace slambox
