/*
 * fcl_adapter.cpp - FCL 0.7 behind the C interface of fcl_adapter.h: planar distance and
 * penetration depth between the robot disc and one obstacle (circle, person or oriented
 * box). Shapes live on the stack; FCL's geometry-pointer overloads of distance() and
 * collide() need no CollisionObject (and so no shared_ptr) for a single pair.
 */
#include "fcl_adapter.h"

#include <fcl/fcl.h>

#include <cmath>

namespace {

/* FCL rejects nothing at radius 0, but keep a tiny positive sphere so its GJK-free
 * primitive paths see a proper shape; 1e-9 m is far below any resolution we use. */
constexpr double kMinRadius = 1e-9;

fcl::Transform3d planar(double x, double y, double yaw)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    tf.translation() << x, y, 0.0;
    return tf;
}

double pair_distance(const fcl::CollisionGeometryd &robot, const fcl::Transform3d &tf_robot,
                     const fcl::CollisionGeometryd &obstacle, const fcl::Transform3d &tf_obstacle)
{
    fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    const double d = fcl::distance(&robot, tf_robot, &obstacle, tf_obstacle, request, result);
    return d > 0.0 ? d : 0.0; /* FCL reports -1 for overlapping shapes */
}

double pair_penetration(const fcl::CollisionGeometryd &robot, const fcl::Transform3d &tf_robot,
                        const fcl::CollisionGeometryd &obstacle, const fcl::Transform3d &tf_obstacle)
{
    fcl::CollisionRequestd request(1, true);
    fcl::CollisionResultd result;
    fcl::collide(&robot, tf_robot, &obstacle, tf_obstacle, request, result);
    if (!result.isCollision())
        return 0.0;
    double depth = 0.0;
    for (size_t i = 0; i < result.numContacts(); ++i)
        depth = std::fmax(depth, result.getContact(i).penetration_depth);
    return depth;
}

} // namespace

extern "C" double gmmrrt_fcl_disc_distance(double x, double y, double robot_radius_m, double cx,
                                           double cy, double radius_m)
{
    const fcl::Sphered robot(std::fmax(robot_radius_m, kMinRadius));
    const fcl::Sphered disc(std::fmax(radius_m, kMinRadius));
    return pair_distance(robot, planar(x, y, 0.0), disc, planar(cx, cy, 0.0));
}

extern "C" double gmmrrt_fcl_box_distance(double x, double y, double robot_radius_m, double cx, double cy,
                                          double width_m, double height_m, double yaw)
{
    const fcl::Sphered robot(std::fmax(robot_radius_m, kMinRadius));
    const fcl::Boxd box(width_m, height_m, 1.0);
    return pair_distance(robot, planar(x, y, 0.0), box, planar(cx, cy, yaw));
}

extern "C" double gmmrrt_fcl_disc_penetration(double x, double y, double robot_radius_m, double cx,
                                              double cy, double radius_m)
{
    const fcl::Sphered robot(std::fmax(robot_radius_m, kMinRadius));
    const fcl::Sphered disc(std::fmax(radius_m, kMinRadius));
    return pair_penetration(robot, planar(x, y, 0.0), disc, planar(cx, cy, 0.0));
}

extern "C" double gmmrrt_fcl_box_penetration(double x, double y, double robot_radius_m, double cx,
                                             double cy, double width_m, double height_m, double yaw)
{
    const fcl::Sphered robot(std::fmax(robot_radius_m, kMinRadius));
    const fcl::Boxd box(width_m, height_m, 1.0);
    return pair_penetration(robot, planar(x, y, 0.0), box, planar(cx, cy, yaw));
}
