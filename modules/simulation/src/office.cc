#include "contour_reg/simulation/office.h"

#include "contour_reg/simulation/paths.h"

#include <string>
#include <vector>

namespace contour_reg::simulation {

namespace {

using V = Eigen::Vector2d;

// A horizontal wall at height y from x0 to x1 with door gaps [d, d + width).
void wallWithDoors(World &world, double y, double x0, double x1, const std::vector<double> &doors, double width) {
  double x = x0;
  for (double d : doors) {
    world.addSegment(V(x, y), V(d, y));
    x = d + width;
  }
  world.addSegment(V(x, y), V(x1, y));
}

}  // namespace

World makeOfficeWorld() {
  World world;
  // Outer walls, with a recess at the east end of the corridor.
  world.addPolygon({V(0, 0), V(30, 0), V(30, 6), V(31.5, 6), V(31.5, 9), V(30, 9), V(30, 16), V(0, 16)});
  // Corridor walls with doors into the rooms.
  wallWithDoors(world, 6.0, 0.0, 30.0, {3.0, 11.0, 19.0, 26.0}, 1.0);
  wallWithDoors(world, 9.0, 0.0, 30.0, {5.0, 14.0, 22.0}, 1.0);
  // Walls between rooms.
  for (double x : {8.0, 16.0, 23.0}) world.addSegment(V(x, 0), V(x, 6));
  for (double x : {10.0, 18.0}) world.addSegment(V(x, 9), V(x, 16));
  // Furniture: desks, cabinets, a meeting table, an L-shaped counter.
  world.addBox(V(1.0, 1.0), V(2.6, 1.8));
  world.addBox(V(5.5, 3.5), V(7.2, 4.3));
  world.addBox(V(9.5, 0.5), V(10.3, 2.5));
  world.addBox(V(12.5, 2.0), V(14.5, 3.2));
  world.addBox(V(17.0, 4.5), V(18.6, 5.3));
  world.addBox(V(24.0, 1.0), V(25.2, 1.6));
  world.addBox(V(27.5, 3.0), V(29.0, 4.5));
  world.addBox(V(2.0, 12.0), V(4.5, 13.2));
  world.addBox(V(7.0, 14.5), V(9.2, 15.3));
  world.addBox(V(12.0, 11.0), V(13.0, 12.0));
  world.addBox(V(15.5, 13.5), V(17.2, 15.0));
  world.addPolygon({V(20.0, 12.0), V(23.0, 12.0), V(23.0, 12.6), V(20.6, 12.6), V(20.6, 14.5), V(20.0, 14.5)});
  world.addPolygon({V(26.0, 11.0), V(27.2, 10.4), V(27.8, 11.6), V(26.6, 12.2)});  // a turned cabinet
  // Pillars along the corridor walls, square and round; round bins and plants.
  world.addBox(V(9.0, 6.0), V(9.4, 6.4));
  world.addBox(V(20.5, 8.6), V(20.9, 9.0));
  world.addCircle(V(16.5, 6.45), 0.25);
  world.addCircle(V(4.6, 4.6), 0.3);
  world.addCircle(V(20.0, 2.0), 0.4);
  world.addCircle(V(27.0, 14.0), 0.35);
  world.addCircle(V(6.8, 10.6), 0.2);
  return world;
}

World makeFurnishedRoom() {
  World world;
  world.addPolygon({{-6.0, -4.0},
                    {7.0, -4.0},
                    {7.0, 1.0},
                    {7.6, 1.0},
                    {7.6, 2.2},
                    {7.0, 2.2},
                    {7.0, 5.0},
                    {-2.0, 5.0},
                    {-2.0, 5.8},
                    {-3.0, 5.8},
                    {-3.0, 5.0},
                    {-6.0, 5.0}});
  world.addBox({-4.8, -3.2}, {-3.6, -2.4});
  world.addBox({2.0, 2.5}, {3.4, 3.3});
  world.addBox({4.2, -2.8}, {5.0, -1.6});
  world.addPolygon({{-2.5, 1.5}, {-1.9, 1.5}, {-1.9, 2.1}, {-2.5, 2.1}});
  world.addPolygon({{0.8, -1.8}, {1.6, -2.3}, {2.0, -1.7}});  // a triangular cabinet
  world.addCircle({-4.0, 3.0}, 0.3);
  return world;
}

World makeDoorRowWorld() {
  World world;
  constexpr double kLength = 60.0, kWidth = 2.4, kDoor = 0.9, kDepth = 0.2;
  world.addSegment(V(0.0, kWidth), V(kLength, kWidth));
  world.addSegment(V(0.0, 0.0), V(0.0, kWidth));
  world.addSegment(V(kLength, 0.0), V(kLength, kWidth));
  // The south wall, broken by a recess every period.
  double x = 0.0;
  for (double door = 0.5 * kDoorRowPeriod; door + kDoor < kLength; door += kDoorRowPeriod) {
    world.addSegment(V(x, 0.0), V(door, 0.0));
    world.addSegment(V(door, 0.0), V(door, -kDepth));
    world.addSegment(V(door, -kDepth), V(door + kDoor, -kDepth));
    world.addSegment(V(door + kDoor, -kDepth), V(door + kDoor, 0.0));
    x = door + kDoor;
  }
  world.addSegment(V(x, 0.0), V(kLength, 0.0));
  return world;
}

std::vector<V> doorRowPath(const std::string &name) {
  if (name == "line") return {V(3.0, 1.2), V(57.0, 1.2)};
  return {};
}

bool isBuiltInWorld(const std::string &map) { return map == "office" || map == "doors"; }

World makeBuiltInWorld(const std::string &map) {
  if (map == "office") return makeOfficeWorld();
  if (map == "doors") return makeDoorRowWorld();
  return {};
}

std::vector<V> builtInPath(const std::string &map, const std::string &name) {
  if (map == "office") return officePath(name);
  if (map == "doors") return doorRowPath(name);
  return {};
}

std::string builtInPathChoices(const std::string &map) {
  if (map == "office") return "the office (S, L, Y, O, line)";
  if (map == "doors") return "the door row (line)";
  return map;
}

}  // namespace contour_reg::simulation
