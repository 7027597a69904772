/*
 * fcl_adapter.h - internal: the few FCL queries the collision world needs, behind a C
 * interface (FCL 0.7 is C++). The robot is a disc (an FCL sphere in the z = 0 plane),
 * circles and people are spheres, boxes are FCL boxes of height 1 m centred on z = 0,
 * so every distance is the planar one. Used when the world is built (collision.c) and by
 * gmmrrt_world_exact_clearance; never inside the planning loop.
 */
#ifndef GMMRRT_FCL_ADAPTER_H
#define GMMRRT_FCL_ADAPTER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Distance (m) between the robot disc of radius robot_radius_m (>= 0) centred at (x, y)
 * and a disc of radius radius_m at (cx, cy); 0 when they touch or overlap. */
double gmmrrt_fcl_disc_distance(double x, double y, double robot_radius_m, double cx, double cy,
                                double radius_m);

/* Distance (m) between the robot disc and a box (centre cx, cy; full sizes w, h; yaw);
 * 0 when they touch or overlap. */
double gmmrrt_fcl_box_distance(double x, double y, double robot_radius_m, double cx, double cy,
                               double width_m, double height_m, double yaw);

/* Penetration depth (m, >= 0) of the robot disc into the disc / box, from FCL's contact
 * query; 0 when they do not overlap. Allocates (FCL's contact vector): not for the loop. */
double gmmrrt_fcl_disc_penetration(double x, double y, double robot_radius_m, double cx, double cy,
                                   double radius_m);
double gmmrrt_fcl_box_penetration(double x, double y, double robot_radius_m, double cx, double cy,
                                  double width_m, double height_m, double yaw);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_FCL_ADAPTER_H */
