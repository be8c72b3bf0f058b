// The classroom-like built-in scene: a closed room of slabs with windows, a blackboard,
// rows of desks and chairs, bookcases full of books and ceiling lamps. It stands in for the
// thesis's Classroom scene (§6: a mostly closed room with 69 materials), so nearly every
// object gets its own procedural material.
#include <array>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/material_recipes.h"
#include "runtime/scene/builtin/scene_builder.h"

namespace memograph::runtime {
namespace {

glm::mat4 at(glm::vec3 p) {
  return glm::translate(glm::mat4(1.0f), p);
}

// A deterministic palette: colour i of n spread around the hue circle, moderate saturation.
glm::vec3 paletteColor(int i, int n, float saturation = 0.6f, float value = 0.7f) {
  const float h = 6.0f * static_cast<float>(i) / static_cast<float>(n);
  const float c = value * saturation;
  const float x = c * (1.0f - std::abs(std::fmod(h, 2.0f) - 1.0f));
  glm::vec3 rgb;
  if (h < 1)
    rgb = {c, x, 0};
  else if (h < 2)
    rgb = {x, c, 0};
  else if (h < 3)
    rgb = {0, c, x};
  else if (h < 4)
    rgb = {0, x, c};
  else if (h < 5)
    rgb = {x, 0, c};
  else
    rgb = {c, 0, x};
  return rgb + glm::vec3(value - c);
}

std::string numbered(const std::string& base, int i) {
  return base + (i < 10 ? "0" : "") + std::to_string(i);
}

struct Room {
  SceneBuilder& b;
  MaterialCost cost;
  std::uint32_t seed = 1;
  RecipeSeed next() { return RecipeSeed{seed++}; }
};

// Floor, ceiling, four walls with three window openings on the +x wall, window panes that
// glow like an overcast sky, sills and radiators.
void addShell(Room& r) {
  SceneBuilder& b = r.b;
  const float W = kClassroom.width, H = kClassroom.height, D = kClassroom.depth, t = 0.2f;
  const auto tiles =
      b.material("Classroom_FloorTiles", tileGraph("Classroom_FloorTiles", {}, r.next(), r.cost));
  const auto ceiling =
      b.material("Classroom_Ceiling",
                 plasterGraph("Classroom_Ceiling", {{0.9f, 0.9f, 0.88f}, 0.9f}, r.next(), r.cost));
  const auto wallA = b.material(
      "Classroom_WallPaint",
      plasterGraph("Classroom_WallPaint", {{0.86f, 0.82f, 0.7f}, 0.85f}, r.next(), r.cost));
  const auto wallB = b.material(
      "Classroom_BackWallPaint",
      plasterGraph("Classroom_BackWallPaint", {{0.62f, 0.72f, 0.66f}, 0.85f}, r.next(), r.cost));
  const auto wainscot = b.material(
      "Classroom_Wainscot",
      paintedMetalGraph("Classroom_Wainscot", {{0.35f, 0.42f, 0.38f}, {0.5f, 0.5f, 0.5f}, 0.05f},
                        r.next(), r.cost));

  b.instance(b.addMesh(boxesMesh("floor", {{{-t, -t, -t}, {W + t, 0, D + t}}})), tiles, at({}));
  b.instance(b.addMesh(boxesMesh("ceiling", {{{-t, H, -t}, {W + t, H + t, D + t}}})), ceiling,
             at({}));
  // The front and back walls run across the corners, so no ray slips between two slabs'
  // edges there.
  b.instance(b.addMesh(boxesMesh("wall_front", {{{-t, 0, -t}, {W + t, H, 0}}})), wallA, at({}));
  b.instance(b.addMesh(boxesMesh("wall_left", {{{-t, 0, 0}, {0, H, D}}})), wallA, at({}));
  b.instance(b.addMesh(boxesMesh("wall_back", {{{-t, 0, D}, {W + t, H, D + t}}})), wallB, at({}));
  // The window wall: below, above and the piers between three openings.
  const std::array<glm::vec2, 3> windows = {glm::vec2{0.75f, 2.25f}, {3.0f, 4.5f}, {5.25f, 6.75f}};
  const float sill = 0.9f, lintel = 2.6f;
  {
    Mesh wall;
    wall.name = "wall_windows";
    appendBox(wall, {W, 0, 0}, {W + t, sill, D});
    appendBox(wall, {W, lintel, 0}, {W + t, H, D});
    float z = 0;
    for (const glm::vec2 w : windows) {
      appendBox(wall, {W, sill, z}, {W + t, lintel, w.x});
      z = w.y;
    }
    appendBox(wall, {W, sill, z}, {W + t, lintel, D});
    b.instance(b.addMesh(std::move(wall)), wallA, at({}));
  }
  // Wainscot panels along the walls without openings.
  b.instance(b.addMesh(boxesMesh("wainscot_left", {{{0, 0, 0}, {0.02f, 1.1f, D}}})), wainscot,
             at({}));
  b.instance(b.addMesh(boxesMesh("wainscot_back", {{{0, 0, D - 0.02f}, {W, 1.1f, D}}})), wainscot,
             at({}));

  const auto sky =
      b.material("Classroom_WindowSky",
                 emitterGraph("Classroom_WindowSky", {{2.6f, 3.0f, 3.6f}, {0.8f, 0.85f, 0.9f}}));
  // Emissive NEE: the graph's constant emission (emitterGraph reads no input).
  b.scene().materials[sky].emissionEstimate = {2.6f, 3.0f, 3.6f};
  b.scene().materials[sky].emissionKind = MaterialRef::EmissionKind::Constant;
  const auto sillMaterial = b.material(
      "Classroom_WindowSill",
      paintedMetalGraph("Classroom_WindowSill", {{0.9f, 0.9f, 0.88f}, {0.6f, 0.6f, 0.6f}, 0.1f},
                        r.next(), r.cost));
  const auto radiatorMaterial = b.material(
      "Classroom_Radiator",
      paintedMetalGraph("Classroom_Radiator", {{0.8f, 0.8f, 0.76f}, {0.5f, 0.5f, 0.5f}, 0.2f},
                        r.next(), r.cost));
  const float paneWidth = windows[0].y - windows[0].x;
  const auto pane =
      b.addMesh(boxesMesh("window_pane", {{{0, 0, 0}, {0.04f, lintel - sill, paneWidth}}}));
  const auto sillMesh =
      b.addMesh(boxesMesh("window_sill", {{{0, 0, -0.05f}, {0.25f, 0.04f, paneWidth + 0.05f}}}));
  const auto radiator =
      b.addMesh(boxesMesh("radiator", {{{0, 0, 0}, {0.12f, 0.6f, 1.2f}},
                                       {{0.02f, -0.15f, 0.1f}, {0.08f, 0, 0.14f}},
                                       {{0.02f, -0.15f, 1.06f}, {0.08f, 0, 1.1f}}}));
  for (const glm::vec2 w : windows) {
    b.instance(pane, sky, at({W + 0.08f, sill, w.x}));
    b.instance(sillMesh, sillMaterial, at({W - 0.25f, sill - 0.04f, w.x}));
    b.instance(radiator, radiatorMaterial, at({W - 0.2f, 0.15f, w.x + 0.15f}));
  }
}

// The front: blackboard with frame and chalk tray, teacher's desk and chair, a door.
void addFront(Room& r) {
  SceneBuilder& b = r.b;
  const float W = kClassroom.width, D = kClassroom.depth;
  const auto board = b.material("Classroom_Blackboard",
                                chalkboardGraph("Classroom_Blackboard", {}, r.next(), r.cost));
  const auto frameWood = b.material(
      "Classroom_BoardFrame",
      woodGraph("Classroom_BoardFrame", {{0.55f, 0.38f, 0.22f}, {0.3f, 0.18f, 0.09f}, 7, 10, 0.5f},
                r.next(), r.cost));
  const auto tray = b.material(
      "Classroom_ChalkTray",
      paintedMetalGraph("Classroom_ChalkTray", {{0.5f, 0.5f, 0.52f}, {0.7f, 0.7f, 0.72f}, 0.5f},
                        r.next(), r.cost));
  const float x0 = W / 2 - 2.0f, x1 = W / 2 + 2.0f;
  b.instance(b.addMesh(boxesMesh("board_frame", {{{x0, 0.9f, 0}, {x1, 2.3f, 0.04f}}})), frameWood,
             at({}));
  b.instance(b.addMesh(boxesMesh("board", {{{x0 + 0.1f, 1.0f, 0.04f}, {x1 - 0.1f, 2.2f, 0.05f}}})),
             board, at({}));
  b.instance(
      b.addMesh(boxesMesh("chalk_tray", {{{x0 + 0.1f, 0.95f, 0.04f}, {x1 - 0.1f, 0.98f, 0.12f}}})),
      tray, at({}));

  const auto teacherWood = b.material(
      "Classroom_TeacherDesk",
      woodGraph("Classroom_TeacherDesk",
                {{0.45f, 0.28f, 0.15f}, {0.22f, 0.12f, 0.06f}, 11, 7, 0.35f}, r.next(), r.cost));
  const auto teacherPanel = b.material(
      "Classroom_TeacherDeskPanel",
      paintedMetalGraph("Classroom_TeacherDeskPanel",
                        {{0.25f, 0.3f, 0.35f}, {0.6f, 0.6f, 0.6f}, 0.15f}, r.next(), r.cost));
  const auto teacherSeat =
      b.material("Classroom_TeacherChair",
                 fabricGraph("Classroom_TeacherChair",
                             {{0.15f, 0.15f, 0.17f}, {0.3f, 0.08f, 0.08f}, 90}, r.next(), r.cost));
  const glm::vec3 desk{W / 2, 0, 1.6f};
  b.instance(
      b.addMesh(boxesMesh("teacher_desk_top", {{{-0.8f, 0.74f, -0.4f}, {0.8f, 0.78f, 0.4f}}})),
      teacherWood, at(desk));
  b.instance(
      b.addMesh(boxesMesh("teacher_desk_body", {{{-0.78f, 0, -0.38f}, {-0.74f, 0.74f, 0.38f}},
                                                {{0.74f, 0, -0.38f}, {0.78f, 0.74f, 0.38f}},
                                                {{-0.74f, 0.2f, -0.38f}, {0.74f, 0.74f, -0.34f}}})),
      teacherPanel, at(desk));
  b.instance(b.addMesh(boxesMesh("teacher_chair", {{{-0.25f, 0.45f, -0.25f}, {0.25f, 0.52f, 0.25f}},
                                                   {{-0.25f, 0.52f, -0.3f}, {0.25f, 1.05f, -0.25f}},
                                                   {{-0.03f, 0, -0.03f}, {0.03f, 0.45f, 0.03f}},
                                                   {{-0.3f, 0, -0.03f}, {0.3f, 0.04f, 0.03f}},
                                                   {{-0.03f, 0, -0.3f}, {0.03f, 0.04f, 0.3f}}})),
             teacherSeat, at(desk + glm::vec3(0, 0, -0.75f)));

  // Door with frame on the left wall, at the back.
  const auto door = b.material(
      "Classroom_Door",
      woodGraph("Classroom_Door", {{0.66f, 0.5f, 0.32f}, {0.42f, 0.3f, 0.18f}, 6, 9, 0.4f},
                r.next(), r.cost));
  const auto doorFrame = b.material(
      "Classroom_DoorFrame",
      paintedMetalGraph("Classroom_DoorFrame", {{0.92f, 0.92f, 0.9f}, {0.5f, 0.5f, 0.5f}, 0.08f},
                        r.next(), r.cost));
  b.instance(b.addMesh(boxesMesh("door", {{{0, 0, D - 1.7f}, {0.05f, 2.1f, D - 0.75f}}})), door,
             at({}));
  b.instance(b.addMesh(boxesMesh("door_frame", {{{0, 0, D - 1.8f}, {0.07f, 2.2f, D - 1.7f}},
                                                {{0, 0, D - 0.75f}, {0.07f, 2.2f, D - 0.65f}},
                                                {{0, 2.1f, D - 1.7f}, {0.07f, 2.2f, D - 0.75f}}})),
             doorFrame, at({}));
}

// Four rows of four double desks, two chairs each: every desk top and chair shell its own
// material, desk frames per row.
void addDesks(Room& r) {
  SceneBuilder& b = r.b;
  const auto top = b.addMesh(boxesMesh("desk_top", {{{-0.6f, 0.72f, -0.3f}, {0.6f, 0.75f, 0.3f}}}));
  const auto frame = b.addMesh(
      boxesMesh("desk_frame", {{{-0.58f, 0, -0.28f}, {-0.54f, 0.72f, -0.24f}},
                               {{0.54f, 0, -0.28f}, {0.58f, 0.72f, -0.24f}},
                               {{-0.58f, 0, 0.24f}, {-0.54f, 0.72f, 0.28f}},
                               {{0.54f, 0, 0.24f}, {0.58f, 0.72f, 0.28f}},
                               {{-0.54f, 0.55f, -0.28f}, {0.54f, 0.57f, 0.1f}},       // book shelf
                               {{-0.54f, 0.68f, -0.28f}, {0.54f, 0.72f, -0.26f}}}));  // front rail
  const auto shell =
      b.addMesh(boxesMesh("chair_shell", {{{-0.21f, 0.44f, -0.2f}, {0.21f, 0.47f, 0.2f}},
                                          {{-0.21f, 0.55f, 0.17f}, {0.21f, 0.88f, 0.2f}}}));
  const auto chairFrame =
      b.addMesh(boxesMesh("chair_frame", {{{-0.19f, 0, -0.18f}, {-0.16f, 0.44f, -0.15f}},
                                          {{0.16f, 0, -0.18f}, {0.19f, 0.44f, -0.15f}},
                                          {{-0.19f, 0, 0.15f}, {-0.16f, 0.88f, 0.18f}},
                                          {{0.16f, 0, 0.15f}, {0.19f, 0.88f, 0.18f}}}));
  const std::array<std::uint32_t, 2> chairFrameMaterials = {
      b.material(
          "Classroom_ChairFrameChrome",
          paintedMetalGraph("Classroom_ChairFrameChrome",
                            {{0.7f, 0.7f, 0.72f}, {0.9f, 0.9f, 0.92f}, 0.8f}, r.next(), r.cost)),
      b.material(
          "Classroom_ChairFrameBlack",
          paintedMetalGraph("Classroom_ChairFrameBlack",
                            {{0.05f, 0.05f, 0.05f}, {0.6f, 0.6f, 0.6f}, 0.2f}, r.next(), r.cost))};
  const std::array<float, 4> rows = {2.8f, 3.9f, 5.0f, 6.1f};
  const std::array<float, 4> columns = {1.4f, 3.1f, 5.9f, 7.6f};
  int deskIndex = 0;
  for (int row = 0; row < 4; ++row) {
    const std::string frameName = numbered("Classroom_DeskFrame", row);
    const auto frameMaterial = b.material(
        frameName,
        paintedMetalGraph(frameName, {paletteColor(row, 4, 0.5f, 0.5f), {0.6f, 0.6f, 0.6f}, 0.2f},
                          r.next(), r.cost));
    for (int col = 0; col < 4; ++col, ++deskIndex) {
      const glm::vec3 p{columns[col], 0.0f, rows[row]};
      const std::string woodName = numbered("Classroom_DeskTop", deskIndex);
      // Oak to walnut, each desk a different tone, grain and ring density.
      const float tone = static_cast<float>(deskIndex) / 15.0f;
      const WoodParams wood{
          glm::mix(glm::vec3(0.72f, 0.55f, 0.34f), glm::vec3(0.45f, 0.3f, 0.18f), tone),
          glm::mix(glm::vec3(0.45f, 0.3f, 0.16f), glm::vec3(0.2f, 0.11f, 0.05f), tone),
          6.0f + static_cast<float>(deskIndex % 5), 6.0f + static_cast<float>(deskIndex % 4) * 2.0f,
          0.35f + 0.02f * static_cast<float>(deskIndex % 6)};
      b.instance(top, b.material(woodName, woodGraph(woodName, wood, r.next(), r.cost)), at(p));
      b.instance(frame, frameMaterial, at(p));
      const std::string plasticName = numbered("Classroom_ChairShell", deskIndex);
      const auto plastic = b.material(
          plasticName, plasticGraph(plasticName,
                                    {paletteColor(deskIndex * 7 % 16, 16, 0.55f, 0.65f),
                                     0.25f + 0.03f * static_cast<float>(deskIndex % 5), 0.1f},
                                    r.next(), r.cost));
      for (float side : {-0.3f, 0.3f}) {
        const glm::vec3 c = p + glm::vec3(side, 0.0f, 0.5f);
        b.instance(shell, plastic, at(c));
        b.instance(chairFrame, chairFrameMaterials[(deskIndex + (side > 0)) % 2], at(c));
      }
    }
  }
}

// Two bookcases on the back wall, three shelves of books each: the books draw from 24
// leather and cloth bindings.
void addBookcases(Room& r) {
  SceneBuilder& b = r.b;
  const float D = kClassroom.depth;
  const float caseWidth = 3.2f, caseDepth = 0.35f, caseHeight = 2.0f, board = 0.03f;
  const auto caseMesh = b.addMesh(
      boxesMesh("bookcase", {{{0, 0, 0}, {board, caseHeight, caseDepth}},
                             {{caseWidth - board, 0, 0}, {caseWidth, caseHeight, caseDepth}},
                             {{0, caseHeight - board, 0}, {caseWidth, caseHeight, caseDepth}},
                             {{0, 0.05f, 0}, {caseWidth, 0.05f + board, caseDepth}},
                             {{0, 0.7f, 0}, {caseWidth, 0.7f + board, caseDepth}},
                             {{0, 1.35f, 0}, {caseWidth, 1.35f + board, caseDepth}},
                             {{0, 0, caseDepth - 0.01f}, {caseWidth, caseHeight, caseDepth}}}));
  // Book sizes (width along the shelf, height, depth).
  const std::array<glm::vec3, 4> bookSizes = {glm::vec3{0.035f, 0.24f, 0.17f},
                                              {0.05f, 0.3f, 0.22f},
                                              {0.03f, 0.2f, 0.15f},
                                              {0.07f, 0.28f, 0.21f}};
  std::array<std::uint32_t, 4> bookMeshes{};
  for (int i = 0; i < 4; ++i) {
    bookMeshes[i] = b.addMesh(
        boxesMesh("book_" + std::to_string(i), {{{0, 0, 0}, bookSizes[i]}}, UvScale{0.25f}));
  }
  std::array<std::uint32_t, 24> bindings{};
  for (int i = 0; i < 24; ++i) {
    const glm::vec3 color =
        paletteColor(i * 5 % 24, 24, 0.65f, 0.25f + 0.25f * static_cast<float>(i % 3));
    if (i % 2 == 0) {
      const std::string name = numbered("Classroom_BookLeather", i / 2);
      bindings[i] = b.material(
          name,
          leatherGraph(name, {color, 0.45f + 0.05f * static_cast<float>(i % 4)}, r.next(), r.cost));
    } else {
      const std::string name = numbered("Classroom_BookCloth", i / 2);
      bindings[i] = b.material(
          name, fabricGraph(name, {color, color * 0.8f, 200.0f + 20.0f * static_cast<float>(i % 5)},
                            r.next(), r.cost));
    }
  }
  int book = 0;
  for (int c = 0; c < 2; ++c) {
    const std::string woodName = numbered("Classroom_Bookcase", c);
    const auto wood = b.material(woodName, woodGraph(woodName,
                                                     {{0.6f - 0.15f * static_cast<float>(c),
                                                       0.45f - 0.12f * static_cast<float>(c),
                                                       0.3f - 0.1f * static_cast<float>(c)},
                                                      {0.35f, 0.22f, 0.12f},
                                                      8,
                                                      8,
                                                      0.5f},
                                                     r.next(), r.cost));
    const glm::vec3 origin{0.6f + static_cast<float>(c) * (caseWidth + 1.0f), 0.0f, D - caseDepth};
    b.instance(caseMesh, wood, at(origin));
    for (float shelfY : {0.05f + board, 0.7f + board, 1.35f + board}) {
      float x = board + 0.02f;
      while (true) {
        const int size = (book * 7 + book / 3) % 4;
        const glm::vec3 s = bookSizes[size];
        if (x + s.x > caseWidth - board - 0.02f)
          break;
        // Books stand against the back of the case; every ninth gap leaves a space.
        if (book % 9 != 8) {
          b.instance(bookMeshes[size], bindings[(book * 11) % 24],
                     at(origin + glm::vec3(x, shelfY, caseDepth - 0.01f - s.z)));
        }
        x += s.x + 0.004f;
        ++book;
      }
    }
  }
}

// Posters and a pin board on the left wall, a waste bin, ceiling lamps with point lights.
void addDetails(Room& r) {
  SceneBuilder& b = r.b;
  const float W = kClassroom.width, H = kClassroom.height;
  const auto poster = b.addMesh(boxesMesh("poster", {{{0, 0, 0}, {0.01f, 0.8f, 0.6f}}}));
  for (int i = 0; i < 4; ++i) {
    const std::string name = numbered("Classroom_Poster", i);
    const auto material = b.material(name, posterGraph(name,
                                                       {paletteColor(i, 4, 0.8f, 0.85f),
                                                        paletteColor(i + 2, 4, 0.7f, 0.5f),
                                                        {0.92f, 0.9f, 0.84f},
                                                        4.0f + 2.0f * static_cast<float>(i)},
                                                       r.next(), r.cost));
    b.instance(poster, material, at({0.02f, 1.4f, 2.4f + 0.9f * static_cast<float>(i)}));
  }
  const auto cork =
      b.material("Classroom_PinBoard", corkGraph("Classroom_PinBoard", {}, r.next(), r.cost));
  b.instance(b.addMesh(boxesMesh("pin_board", {{{0, 0, 0}, {0.02f, 1.0f, 1.4f}}})), cork,
             at({0.02f, 1.1f, 0.6f}));
  const auto binMaterial = b.material(
      "Classroom_WasteBin",
      plasticGraph("Classroom_WasteBin", {{0.1f, 0.25f, 0.5f}, 0.4f, 0.05f}, r.next(), r.cost));
  Mesh bin;
  bin.name = "waste_bin";
  appendCylinder(bin, {0, 0, 0}, 0.16f, 0.4f, 24);
  b.instance(b.addMesh(std::move(bin)), binMaterial, at({W - 0.5f, 0, 0.5f}));

  const auto housing = b.material(
      "Classroom_LampHousing",
      paintedMetalGraph("Classroom_LampHousing", {{0.85f, 0.85f, 0.85f}, {0.7f, 0.7f, 0.7f}, 0.05f},
                        r.next(), r.cost));
  const auto panel = b.material(
      "Classroom_LampPanel",
      emitterGraph("Classroom_LampPanel", {{12.0f, 11.5f, 10.5f}, {0.95f, 0.95f, 0.95f}}));
  b.scene().materials[panel].emissionEstimate = {12.0f, 11.5f, 10.5f};  // as the sky's
  b.scene().materials[panel].emissionKind = MaterialRef::EmissionKind::Constant;
  const auto housingMesh =
      b.addMesh(boxesMesh("lamp_housing", {{{-0.6f, -0.08f, -0.15f}, {0.6f, 0, 0.15f}}}));
  const auto panelMesh =
      b.addMesh(boxesMesh("lamp_panel", {{{-0.55f, -0.1f, -0.1f}, {0.55f, -0.08f, 0.1f}}}));
  for (float x : {2.2f, 4.5f, 6.8f}) {
    for (float z : {2.0f, 5.0f}) {
      b.instance(housingMesh, housing, at({x, H, z}));
      b.instance(panelMesh, panel, at({x, H, z}));
      Light light;
      light.type = LightType::Point;
      light.position = {x, H - 0.25f, z};
      light.intensity = glm::vec3(6.0f, 5.8f, 5.3f);
      b.scene().lights.push_back(light);
    }
  }
}

}  // namespace

Scene makeClassroomScene(const BuiltinSceneOptions& options) {
  SceneBuilder builder(options.onGeometry);
  Room room{builder, options.materialCost};
  addShell(room);
  addFront(room);
  addDesks(room);
  addBookcases(room);
  addDetails(room);
  Scene& scene = builder.scene();
  scene.camera.position = {8.2f, 1.6f, 7.0f};
  scene.camera.target = {3.5f, 1.1f, 0.5f};
  scene.camera.verticalFovDegrees = 60.0f;
  // A closed room: the environment is only seen through nothing, so keep it black.
  scene.environment.constantRadiance = glm::vec3(0.0f);
  // Off unless asked for: the lamps' point lights already light the room (builtin_scenes.h).
  scene.emissiveLightSampling = options.emissiveNee.value_or(false);
  return std::move(scene);
}

}  // namespace memograph::runtime
