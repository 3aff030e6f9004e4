#include "render_fw.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>

#include "apu_image.hpp"
#include "render_kernels.hpp"
#include "render_layout.hpp"

namespace mc1::render {

using namespace layout;

// An FP24 number as an integer of the same order (sign and magnitude to two's
// complement; both zeros are 0): how the MPU compares FP24 values.
std::int32_t order_key(std::uint32_t fp24) {
  const auto magnitude = static_cast<std::int32_t>(fp24 & 0x7FFFFF);
  return (fp24 & 0x800000) ? -magnitude : magnitude;
}

// An empty box of order keys, and a box grown to hold another.
using KeyBox = std::array<std::int32_t, 6>;  // RenderFirmware::Box
constexpr KeyBox kEmptyBox = {INT32_MAX, INT32_MAX, INT32_MAX, INT32_MIN, INT32_MIN, INT32_MIN};
void grow_box(KeyBox& b, const KeyBox& p) {
  for (int c = 0; c < 3; ++c) {
    b[c] = std::min(b[c], p[c]);
    b[3 + c] = std::max(b[3 + c], p[3 + c]);
  }
}

// ---------------------------------------------------------------- kernels

const std::vector<apu::Encoded>& kernel_words(const std::string& name) {
  static std::map<std::string, std::vector<apu::Encoded>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  for (const auto& k : kernel_images()) {
    if (name == k.name) {
      std::string bytes(reinterpret_cast<const char*>(k.bytes), k.size);
      return cache.emplace(name, apu::parse_image(bytes, name)).first->second;
    }
  }
  throw std::out_of_range("no renderer kernel named " + name);
}

// ---------------------------------------------------------------- links, costs

void DirectLink::wait_swap() {
  std::uint64_t spent = 0;
  while (drv_.data_ready()) {
    if (drv_.state() != apu::RunState::Running || spent > max_cycles_)
      throw std::runtime_error("render: APU stopped waiting for a data bank (state " +
                               std::to_string(static_cast<int>(drv_.state())) + ", fault " +
                               apu::fault_name(drv_.engine().fault()) + ")");
    spent += drv_.run(16);  // the MPU polls every 16 APU cycles
  }
}

void DirectLink::wait_halt() {
  if (drv_.state() == apu::RunState::Running) drv_.run_until_done(max_cycles_);
  if (drv_.state() != apu::RunState::Halted)
    throw std::runtime_error(std::string("render: APU did not halt: fault ") +
                             apu::fault_name(drv_.engine().fault()));
}

StepCost& StepCost::operator+=(const StepCost& o) {
  apu_cycles += o.apu_cycles;
  apu_runs += o.apu_runs;
  batches += o.batches;
  word_copies += o.word_copies;
  list_elements += o.list_elements;
  sort_compares += o.sort_compares;
  apu_commands += o.apu_commands;
  return *this;
}

const char* step_name(Step s) {
  static const char* names[kSteps] = {"step1 transform", "step2 block lists", "s1 hidden surface",
                                      "s2 shadows", "s3 shading", "s4 reflection/transmission",
                                      "output"};
  return names[static_cast<int>(s)];
}

StepCost RenderStats::total() const {
  StepCost t;
  for (const auto& s : step) t += s;
  return t;
}

// ---------------------------------------------------------------- banks, streams

RenderFirmware::RenderFirmware(ApuLink& link) : link_(link) { invalidate_banks(); }

RenderFirmware::RenderFirmware(apu::ApuDriver& drv)
    : own_link_(std::make_unique<DirectLink>(drv)), link_(*own_link_) {
  invalidate_banks();
}

void RenderFirmware::use_kernels(KernelTable table) {
  kernels_ = std::make_unique<const KernelTable>(std::move(table));
  apu_prog_.clear();  // the program banks may hold the library's copy
  mpu_prog_.clear();
}

void RenderFirmware::invalidate_banks() {
  for (auto& b : banks_) {
    b.scene_valid = false;
    b.slot_prim.assign(kPrimSlots, -1);
  }
  apu_prog_.clear();
  mpu_prog_.clear();
}

void RenderFirmware::write(std::uint16_t addr, const std::uint32_t* w, std::size_t n, Step step) {
  link_.apu().load_data(addr, w, n);
  link_.copy_words(n);
  stats_.step[static_cast<int>(step)].word_copies += n;
}

std::vector<std::uint32_t> RenderFirmware::read(std::uint16_t addr, std::size_t n, Step step) {
  link_.copy_words(n);
  stats_.step[static_cast<int>(step)].word_copies += n;
  return link_.apu().read_results(addr, n);
}

void RenderFirmware::ensure_scene(Step step) {
  if (mpu_bank().scene_valid) return;
  write(C_D0, scene_words_.data(), scene_words_.size(), step);
  mpu_bank().scene_valid = true;
}

std::vector<int> RenderFirmware::place_prims(const std::vector<int>& prims, Step step) {
  if (prims.size() > static_cast<std::size_t>(kPrimSlots)) throw std::logic_error("place_prims: too many");
  std::vector<int> slots(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) {
    slots[i] = static_cast<int>(i);
    if (mpu_bank().slot_prim[i] == prims[i]) continue;
    write(static_cast<std::uint16_t>(PRIMS + P_SIZE * i), view_.prims.at(prims[i]).data(), P_SIZE, step);
    mpu_bank().slot_prim[i] = prims[i];
  }
  return slots;
}

void RenderFirmware::use_kernel(const std::string& name, Step step) {
  auto& cost = stats_.step[static_cast<int>(step)];
  auto& drv = link_.apu();
  if (apu_prog_ == name && !drv.program_ready()) return;
  if (mpu_prog_ != name) {
    const std::vector<apu::Encoded>* table_words = nullptr;
    if (kernels_) {
      const auto it = kernels_->find(name);
      if (it == kernels_->end())
        throw std::runtime_error("render: no kernel '" + name + "' among the " + std::to_string(kernels_->size()) +
                                 " the firmware was given");
      table_words = &it->second;
    }
    const auto& words = table_words ? *table_words : kernel_words(name);
    drv.load_program(words);
    link_.copy_words(8 * words.size());
    cost.word_copies += 8 * words.size();
    mpu_prog_ = name;
  }
  drv.hand_over_program();
  link_.apu_commands(1);
  cost.apu_commands += 1;
  std::swap(apu_prog_, mpu_prog_);  // start() takes the hand-over
}

template <class Fill, class Drain>
void RenderFirmware::stream(const std::string& kernel, int items, Step step, Fill fill, Drain drain) {
  if (items <= 0) return;
  auto& cost = stats_.step[static_cast<int>(step)];
  auto& drv = link_.apu();
  use_kernel(kernel, step);
  const std::uint32_t zero = 0;
  fill(0);
  drv.hand_over_data();
  const std::uint64_t c0 = drv.engine().cycle();
  drv.start(0);
  link_.apu_commands(2);
  cost.apu_commands += 2;
  cost.apu_runs += 1;
  for (int i = 1; i <= items; ++i) {
    link_.wait_swap();
    mpu_bank_ ^= 1;
    if (i >= 2) drain(i - 2);
    if (i < items) {
      fill(i);
    } else {
      write(COUNT, &zero, 1, step);  // the end of the stream
    }
    drv.hand_over_data();
    link_.apu_commands(1);
    cost.apu_commands += 1;
  }
  link_.wait_swap();
  mpu_bank_ ^= 1;
  drain(items - 1);
  link_.wait_halt();
  cost.apu_cycles += drv.engine().cycle() - c0;
  cost.batches += static_cast<std::uint64_t>(items);
}

// ---------------------------------------------------------------- scene

void RenderFirmware::load_view_scene(const ViewScene& view) {
  if (view.lights.size() > static_cast<std::size_t>(kMaxLights) ||
      view.materials.size() > static_cast<std::size_t>(kMaxMaterials))
    throw std::invalid_argument("render: at most 8 lights and 16 materials");
  view_ = view;
  scene_words_.assign(PRIMS - C_D0, 0);
  std::copy(view.constants.begin(), view.constants.end(), scene_words_.begin());
  for (std::size_t l = 0; l < view.lights.size(); ++l)
    std::copy(view.lights[l].begin(), view.lights[l].end(), scene_words_.begin() + (LIGHTS - C_D0) + L_SIZE * l);
  for (std::size_t m = 0; m < view.materials.size(); ++m)
    std::copy(view.materials[m].begin(), view.materials[m].end(),
              scene_words_.begin() + (MATS - C_D0) + M_SIZE * m);
  for (auto& b : banks_) {
    b.scene_valid = false;
    b.slot_prim.assign(kPrimSlots, -1);
  }
  project_boxes();
  build_shadow_lists();
  build_solid_regions();
  // Per object the union of its triangles' padded boxes (s4's culling).
  object_tri_box_.assign(view_.objects.size(), kEmptyBox);
  for (std::size_t o = 0; o < view_.objects.size(); ++o) {
    const auto& obj = view_.objects[o];
    for (int q = obj.first_prim; q < obj.first_prim + obj.prim_count; ++q) {
      const std::uint32_t type = view_.prims[q][P_TYPE];
      if (type == kTriangle || type == kPseudoTriangle) grow_box(object_tri_box_[o], prim_box_[q]);
    }
    stats_.step[static_cast<int>(Step::BlockLists)].list_elements += obj.prim_count;
  }
}

// ---------------------------------------------------------------- step 1: r_xform

namespace {
// r_xform's batch words (r_xform.apu header).
constexpr int X_R = 2, X_EYE = 11, X_LOOK = 16, X_UP = 19, X_FOV = 22, X_W = 23, X_H = 24, X_DEG = 25;
constexpr int kItems = 640, kItemSize = 32, kItemsPerBatch = (4096 - kItems) / kItemSize;
constexpr std::uint32_t kPiOver360 = 0x381DF4;  // fp24(pi / 360), degrees to half-angle radians
constexpr std::uint32_t kBig = 0x7ABC17;        // fp24(1e18): "no hit"
bool positive(std::uint32_t fp24) { return !(fp24 & 0x800000) && (fp24 & 0x7F0000); }
}  // namespace

void RenderFirmware::load_scene(const SceneImage& img) {
  constexpr Step step = Step::Transform;
  if (img.lights.size() > static_cast<std::size_t>(kMaxLights) ||
      img.materials.size() > static_cast<std::size_t>(kMaxMaterials))
    throw std::invalid_argument("render: at most 8 lights and 16 materials");
  // The camera (mode 0).
  std::array<std::uint32_t, 9> rot{};
  std::array<std::uint32_t, 32> cam{};  // words C_D0 .. C_D0 + 31 as r_xform left them
  stream("r_xform", 1, step,
         [&](int) {
           std::array<std::uint32_t, 26> w{};
           w[COUNT] = 1;
           w[H_MODE] = 0;
           std::copy(img.eye.begin(), img.eye.end(), w.begin() + X_EYE);
           std::copy(img.look_at.begin(), img.look_at.end(), w.begin() + X_LOOK);
           std::copy(img.up.begin(), img.up.end(), w.begin() + X_UP);
           w[X_FOV] = img.fov_deg;
           w[X_W] = static_cast<std::uint32_t>(img.width);
           w[X_H] = static_cast<std::uint32_t>(img.height);
           w[X_DEG] = kPiOver360;
           write(1, w.data() + 1, w.size() - 1, step);
           write(COUNT, w.data(), 1, step);
         },
         [&](int) {
           const auto r = read(X_R, 9, step);
           std::copy(r.begin(), r.end(), rot.begin());
           const auto c = read(C_D0, 32, step);
           std::copy(c.begin(), c.end(), cam.begin());
         });
  for (auto& b : banks_) b.scene_valid = false;  // the camera batch wrote constants

  // Everything else (mode 1), in place: lights, checker frames, triangles,
  // ellipsoids, object boxes.
  struct Item {
    std::array<std::uint32_t, kItemSize> w{};
  };
  std::vector<Item> items;
  auto add = [&](int kind, const std::uint32_t* in, int at, int n) {
    Item it;
    it.w[0] = static_cast<std::uint32_t>(kind);
    std::copy(in, in + n, it.w.begin() + at);
    items.push_back(it);
    return static_cast<int>(items.size()) - 1;
  };
  std::vector<int> light_item, mat_item, prim_item, box_item;
  for (const auto& l : img.lights) light_item.push_back(add(1, l.data(), 1, 3));
  for (const auto& m : img.materials) {
    const int k = add(2, m.w.data() + M_CKO, 1, 9);
    items[k].w[10] = m.checker_scale;
    mat_item.push_back(k);
  }
  for (const auto& p : img.prims) {
    int k = -1;
    if (p.type == kTriangle || p.type == kPseudoTriangle) {
      k = add(3, p.w.data(), 1, 12);
      std::copy(p.w.begin() + 12, p.w.begin() + 21, items[k].w.begin() + 22);
    } else if (p.type == kEllipsoid) {
      k = add(4, p.w.data(), 1, 12);
    }
    prim_item.push_back(k);
  }
  for (const auto& o : img.objects) {
    const int k = add(5, o.box_min.data(), 1, 3);
    std::copy(o.box_max.begin(), o.box_max.end(), items[k].w.begin() + 4);
    box_item.push_back(k);
  }
  const int batches = (static_cast<int>(items.size()) + kItemsPerBatch - 1) / kItemsPerBatch;
  stream("r_xform", batches, step,
         [&](int b) {
           const int first = b * kItemsPerBatch;
           const int n = std::min(kItemsPerBatch, static_cast<int>(items.size()) - first);
           for (int i = 0; i < n; ++i)
             write(static_cast<std::uint16_t>(kItems + kItemSize * i), items[first + i].w.data(), kItemSize, step);
           write(X_R, rot.data(), 9, step);
           write(X_EYE, img.eye.data(), 3, step);
           const std::uint32_t head[2] = {static_cast<std::uint32_t>(n), 1};
           write(H_MODE, head + 1, 1, step);
           write(COUNT, head, 1, step);
         },
         [&](int b) {
           const int first = b * kItemsPerBatch;
           const int n = std::min(kItemsPerBatch, static_cast<int>(items.size()) - first);
           for (int i = 0; i < n; ++i) {
             const auto back = read(static_cast<std::uint16_t>(kItems + kItemSize * i), 28, step);
             std::copy(back.begin(), back.end(), items[first + i].w.begin());
           }
         });
  for (auto& b : banks_) b.scene_valid = false;

  // The view scene: integer copies of r_xform's results into the records.
  ViewScene v;
  v.width = img.width;
  v.height = img.height;
  v.max_depth = img.max_depth;
  std::copy(cam.begin(), cam.end(), v.constants.begin());
  v.constants[C_EPS - C_D0] = img.epsilon;
  v.constants[C_BIG - C_D0] = kBig;
  v.constants[C_NLIGHTS - C_D0] = static_cast<std::uint32_t>(img.lights.size());
  std::copy(img.background.begin(), img.background.end(), v.constants.begin() + (C_BG - C_D0));
  for (std::size_t l = 0; l < img.lights.size(); ++l) {
    std::array<std::uint32_t, 8> w{};
    std::copy(items[light_item[l]].w.begin() + 1, items[light_item[l]].w.begin() + 4, w.begin() + L_POS);
    std::copy(img.lights[l].begin() + 3, img.lights[l].end(), w.begin() + L_I);
    v.lights.push_back(w);
  }
  for (std::size_t m = 0; m < img.materials.size(); ++m) {
    auto w = img.materials[m].w;
    std::copy(items[mat_item[m]].w.begin() + 1, items[mat_item[m]].w.begin() + 10, w.begin() + M_CKO);
    v.materials.push_back(w);
  }
  for (std::size_t o = 0; o < img.objects.size(); ++o) {
    const auto& oi = img.objects[o];
    ViewScene::Object vo;
    vo.solid = oi.solid;
    const auto& mw = img.materials.at(oi.material).w;
    vo.secondary = positive(mw[M_KS]) || positive(mw[M_KT]);
    vo.first_prim = oi.first_prim;
    vo.prim_count = oi.prim_count;
    std::copy(items[box_item[o]].w.begin() + 1, items[box_item[o]].w.begin() + 7, vo.box.begin());
    v.objects.push_back(vo);
  }
  for (std::size_t i = 0; i < img.prims.size(); ++i) {
    const auto& p = img.prims[i];
    std::array<std::uint32_t, 32> w{};
    w[P_TYPE] = static_cast<std::uint32_t>(p.type);
    w[P_MAT] = static_cast<std::uint32_t>(MATS + M_SIZE * img.objects.at(p.object).material);
    w[P_SOLID] = img.objects[p.object].solid ? 1 : 0;
    w[P_ID] = static_cast<std::uint32_t>(i);
    const auto& x = prim_item[i] >= 0 ? items[prim_item[i]].w : items.front().w;
    if (p.type == kTriangle || p.type == kPseudoTriangle) {
      std::copy(x.begin() + 1, x.begin() + 19, w.begin() + P_P0);   // P0 E1 E2 N UA VA
      std::copy(x.begin() + 19, x.begin() + 28, w.begin() + P_VN0);
    } else if (p.type == kEllipsoid) {
      std::copy(x.begin() + 1, x.begin() + 13, w.begin() + P_A);    // A, b
    } else {
      std::copy(p.w.begin(), p.w.begin() + 16, w.begin() + P_Q);    // world: a1..a10, box
    }
    v.prims.push_back(w);
    v.prim_object.push_back(p.object);
  }
  load_view_scene(v);
}

// ---------------------------------------------------------------- step 2: block lists

bool RenderFirmware::ScreenRect::overlaps(const Block& b) const {
  if (status == kBehind) return false;
  if (status == kWholeScreen) return true;
  return i0 <= b.x0 + b.w - 1 && i1 >= b.x0 && j0 <= b.y0 + b.h - 1 && j1 >= b.y0;
}

// fig. 5: every object box (four points: x / z and y / z are extreme at
// (min, min, zmin), (max, max, zmin), (min, min, zmax), (max, max, zmax)) and
// every triangle (its vertices) projected on the screen by r_box, once per
// frame; the MPU keeps the integer rectangles.
void RenderFirmware::project_boxes() {
  constexpr Step step = Step::BlockLists;
  constexpr int kSize = 16, kPerBatch = (4096 - LISTS) / kSize;
  struct Item {
    std::array<std::uint32_t, 13> w{};
    ScreenRect* out = nullptr;
    int triangle = -1;
  };
  object_rect_.assign(view_.objects.size(), ScreenRect{});
  prim_rect_.assign(view_.prims.size(), ScreenRect{});
  prim_box_.assign(view_.prims.size(), {});
  std::vector<Item> items;
  for (std::size_t o = 0; o < view_.objects.size(); ++o) {
    const auto& b = view_.objects[o].box;  // min xyz, max xyz
    Item it;
    const int corner[4][3] = {{0, 1, 2}, {3, 4, 2}, {0, 1, 5}, {3, 4, 5}};
    for (int p = 0; p < 4; ++p)
      for (int c = 0; c < 3; ++c) it.w[1 + 3 * p + c] = b[corner[p][c]];
    it.out = &object_rect_[o];
    items.push_back(it);
  }
  for (std::size_t k = 0; k < view_.prims.size(); ++k) {
    const auto& p = view_.prims[k];
    if (p[P_TYPE] != kTriangle && p[P_TYPE] != kPseudoTriangle) continue;
    Item it;
    it.w[0] = 1;
    std::copy(p.begin() + P_P0, p.begin() + P_P0 + 9, it.w.begin() + 1);  // v0, E1, E2
    it.out = &prim_rect_[k];
    it.triangle = static_cast<int>(k);
    items.push_back(it);
  }
  const int batches = (static_cast<int>(items.size()) + kPerBatch - 1) / kPerBatch;
  auto count_of = [&](int b) { return std::min(kPerBatch, static_cast<int>(items.size()) - b * kPerBatch); };
  stream("r_box", batches, step,
         [&](int b) {
           ensure_scene(step);
           for (int i = 0; i < count_of(b); ++i)
             write(static_cast<std::uint16_t>(LISTS + kSize * i), items[b * kPerBatch + i].w.data(), 13, step);
           const std::uint32_t count = static_cast<std::uint32_t>(count_of(b));
           write(COUNT, &count, 1, step);
         },
         [&](int b) {
           for (int i = 0; i < count_of(b); ++i) {
             const Item& it = items[b * kPerBatch + i];
             const auto v = read(static_cast<std::uint16_t>(LISTS + kSize * i), it.triangle >= 0 ? 11 : 5, step);
             if (it.triangle >= 0)
               for (int c = 0; c < 6; ++c) prim_box_[it.triangle][c] = order_key(v[5 + c]);
             ScreenRect& r = *it.out;
             r.status = static_cast<int>(v[0]);
             r.i0 = static_cast<std::int16_t>(v[1]);
             r.i1 = static_cast<std::int16_t>(v[2]);
             r.j0 = static_cast<std::int16_t>(v[3]);
             r.j1 = static_cast<std::int16_t>(v[4]);
           }
         });
}

// fig. 6, once per frame after step 1: for each object A and light L, the
// objects B whose view box meets the box of A's box and L (r_slist); then
// the primitives of those objects as candidate lists.
void RenderFirmware::build_shadow_lists() {
  constexpr Step step = Step::Shadows;
  constexpr int kSize = 16, kPerBatch = (4096 - LISTS) / kSize;
  const int nobj = static_cast<int>(view_.objects.size());
  const int nlights = static_cast<int>(view_.lights.size());
  struct Item {
    std::array<std::uint32_t, 15> w{};
    int a = 0, l = 0, b = 0;
  };
  std::vector<Item> items;
  for (int a = 0; a < nobj; ++a)
    for (int l = 0; l < nlights; ++l)
      for (int b = 0; b < nobj; ++b) {
        if (view_.objects[a].prim_count == 0 || view_.objects[b].prim_count == 0) continue;
        Item it{{}, a, l, b};
        std::copy(view_.objects[a].box.begin(), view_.objects[a].box.end(), it.w.begin());
        std::copy(view_.lights[l].begin() + L_POS, view_.lights[l].begin() + L_POS + 3, it.w.begin() + 6);
        std::copy(view_.objects[b].box.begin(), view_.objects[b].box.end(), it.w.begin() + 9);
        items.push_back(it);
      }
  shadow_objects_.assign(static_cast<std::size_t>(nobj) * nlights, {});
  const int batches = (static_cast<int>(items.size()) + kPerBatch - 1) / kPerBatch;
  auto count_of = [&](int b) { return std::min(kPerBatch, static_cast<int>(items.size()) - b * kPerBatch); };
  stream("r_slist", batches, step,
         [&](int b) {
           ensure_scene(step);
           for (int i = 0; i < count_of(b); ++i)
             write(static_cast<std::uint16_t>(LISTS + kSize * i), items[b * kPerBatch + i].w.data(), 15, step);
           const std::uint32_t count = static_cast<std::uint32_t>(count_of(b));
           write(COUNT, &count, 1, step);
         },
         [&](int b) {
           for (int i = 0; i < count_of(b); ++i) {
             const Item& it = items[b * kPerBatch + i];
             if (read(static_cast<std::uint16_t>(LISTS + kSize * i + 15), 1, step)[0])
               shadow_objects_[static_cast<std::size_t>(it.a) * nlights + it.l].push_back(it.b);
           }
         });
  lists_.assign(2, {});
  for (int p = 0; p < static_cast<int>(view_.prims.size()); ++p) lists_[1].push_back(p);
}

BlockList RenderFirmware::build_block_list(const Block& block) {
  auto& cost = stats_.step[static_cast<int>(Step::BlockLists)];
  BlockList bl;
  bl.block = block;
  // The objects whose projected box (r_box) overlaps the block. Sort key:
  // the nearest distance of the box along the view axis, -max z (the view
  // looks down -z), 0 if the box reaches the eye plane; as a non-negative
  // FP24 number it orders as an integer.
  std::vector<std::pair<std::uint32_t, int>> keyed;
  for (int o = 0; o < static_cast<int>(view_.objects.size()); ++o) {
    cost.list_elements += 1;
    if (view_.objects[o].prim_count == 0 || !object_rect_.at(o).overlaps(block)) continue;
    const std::uint32_t zmax = view_.objects[o].box[5];
    // distance = -zmax, or 0 when the box contains the eye plane
    const std::uint32_t key = (zmax & 0x800000) ? (zmax & 0x7FFFFF) : 0;
    keyed.emplace_back(key, o);
  }
  std::stable_sort(keyed.begin(), keyed.end(), [&](const auto& a, const auto& b) {
    ++cost.sort_compares;
    return a.first < b.first;
  });
  link_.sort_compares(cost.sort_compares);
  for (const auto& [key, o] : keyed) {
    bl.objects.push_back(o);
    bl.load += view_.objects[o].secondary ? 4 : 1;
  }
  return bl;
}

// ---------------------------------------------------------------- s1/s2/s4: r_cast

// The batches of `plans` as r_cast / r_inside streams, one per chunk level
// (pass c + 1 of a batch needs pass c's results): fill(plan, c, slots) with
// chunk c's primitives placed in the bank's slots, drain(plan) after the run.
template <class Fill, class Drain>
void RenderFirmware::stream_chunks(const std::string& kernel, const std::vector<BatchPlan>& plans, Step step,
                                   Fill fill, Drain drain) {
  std::size_t levels = 0;
  for (const auto& p : plans) levels = std::max(levels, p.chunks.size());
  for (std::size_t c = 0; c < levels; ++c) {
    std::vector<int> items;
    for (int b = 0; b < static_cast<int>(plans.size()); ++b)
      if (plans[b].chunks.size() > c) items.push_back(b);
    stream(kernel, static_cast<int>(items.size()), step,
           [&](int item) {
             const BatchPlan& p = plans[items[item]];
             ensure_scene(step);
             fill(p, c, place_prims(p.chunks[c], step));
           },
           [&](int item) { drain(plans[items[item]]); });
  }
}

// Items (rays) in batches of at most kRaysPerBatch, in order, whose keys
// (candidate lists) number at most 8 per batch; per batch the union of the
// keys' primitives in chunks of kPrimSlots. Chunk c + 1 of a batch continues
// chunk c's results, so each chunk level is one stream. `always_run`: a
// batch whose keys name no primitive still gets one (empty) chunk.
std::vector<RenderFirmware::BatchPlan> RenderFirmware::plan_batches(
    int items, const std::function<int(int)>& key_of, const std::function<const std::vector<int>&(int)>& prims_of,
    bool always_run, StepCost& cost) {
  constexpr int kListsPerBatch = 8;
  std::vector<BatchPlan> plans;
  for (int i = 0; i < items;) {
    BatchPlan p;
    p.first = i;
    while (i < items && p.n < kRaysPerBatch) {
      const int key = key_of(i);
      if (std::find(p.keys.begin(), p.keys.end(), key) == p.keys.end()) {
        if (static_cast<int>(p.keys.size()) == kListsPerBatch) break;
        p.keys.push_back(key);
      }
      ++p.n;
      ++i;
    }
    std::set<int> all;
    for (int key : p.keys) {
      const std::vector<int>& prims = prims_of(key);
      all.insert(prims.begin(), prims.end());
      cost.list_elements += prims.size();
    }
    std::vector<int> chunk;
    for (int prim : all) {
      chunk.push_back(prim);
      if (static_cast<int>(chunk.size()) == kPrimSlots) p.chunks.push_back(std::move(chunk)), chunk.clear();
    }
    if (!chunk.empty() || (always_run && p.chunks.empty())) p.chunks.push_back(chunk);
    plans.push_back(std::move(p));
  }
  return plans;
}

void RenderFirmware::cast(std::vector<Ray>& rays, const std::vector<std::vector<int>>& lists, Step step) {
  constexpr int kListWords = 48;
  auto& cost = stats_.step[static_cast<int>(step)];
  // Every batch runs (a ray with no candidates still gets its O, D, t).
  const std::vector<BatchPlan> plans = plan_batches(
      static_cast<int>(rays.size()), [&](int i) { return rays[i].list; },
      [&](int l) -> const std::vector<int>& { return lists[l]; }, true, cost);
  auto fill = [&](const BatchPlan& p, std::size_t c, const std::vector<int>& slots) {
    const auto& chunk = p.chunks[c];
    std::map<int, int> slot_of;
    for (std::size_t k = 0; k < chunk.size(); ++k) slot_of[chunk[k]] = slots[k];
    std::vector<std::uint32_t> list_words(kListWords);
    std::vector<int> list_n(p.keys.size());
    for (std::size_t k = 0; k < p.keys.size(); ++k) {
      int n = 0;
      for (int prim : lists[p.keys[k]]) {
        auto it = slot_of.find(prim);
        if (it != slot_of.end()) list_words[n++] = static_cast<std::uint32_t>(it->second);
      }
      cost.list_elements += lists[p.keys[k]].size();
      list_n[k] = n;
      if (n) write(static_cast<std::uint16_t>(LISTS + kListWords * k), list_words.data(), n, step);
    }
    for (int j = 0; j < p.n; ++j) {
      auto rec = rays[p.first + j].rec;
      const int k = static_cast<int>(std::find(p.keys.begin(), p.keys.end(), rays[p.first + j].list) -
                                     p.keys.begin());
      rec[R_LIST] = static_cast<std::uint32_t>(LISTS + kListWords * k);
      rec[R_LISTN] = static_cast<std::uint32_t>(list_n[k]);
      if (c > 0) {  // a later pass: the ray's data as the earlier pass left it
        if (rec[R_KIND] == 1 && rec[R_ID] != kNoHit) rec[R_LISTN] = 0;  // already blocked
        rec[R_KIND] = rec[R_KIND] == 2 || rec[R_KIND] == 5 ? 3 : rec[R_KIND] == 1 ? 4 : rec[R_KIND];
      }
      write(static_cast<std::uint16_t>(RAYS + R_SIZE * j), rec.data(), R_SLOT + 1, step);
      const int from = rays[p.first + j].from;
      static_assert(R_TMIN == R_FROM + 1, "R_FROM, R_TMIN are written together");
      const std::uint32_t tail[2] = {from < 0 ? kNoHit : static_cast<std::uint32_t>(from), rec[R_TMIN]};
      write(static_cast<std::uint16_t>(RAYS + R_SIZE * j + R_FROM), tail, 2, step);
    }
    const std::uint32_t count = static_cast<std::uint32_t>(p.n);
    write(COUNT, &count, 1, step);
  };
  auto drain = [&](const BatchPlan& p) {
    for (int j = 0; j < p.n; ++j) {
      auto back = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j), R_SLOT + 1, step);
      auto& rec = rays[p.first + j].rec;
      for (int w = R_O; w <= R_T; ++w) rec[w] = back[w];
      rec[R_ID] = back[R_ID];
      rec[R_SLOT] = back[R_SLOT];
    }
  };
  stream_chunks("r_cast", plans, step, fill, drain);
}

// ---------------------------------------------------------------- s1: r_scan

// The block in tiles of at most Z_PIXELS pixels (whole rows where they fit);
// per tile the triangles whose projected rectangle meets it, clipped, in
// chunks of kPrimSlots. Chunk c + 1 of a tile continues chunk c's Z-buffer,
// so (as in cast) each chunk level is one stream.
std::vector<RenderFirmware::ZEntry> RenderFirmware::scan_convert(const Block& b,
                                                                 const std::vector<int>& triangles) {
  constexpr Step step = Step::HiddenSurface;
  auto& cost = stats_.step[static_cast<int>(step)];
  struct Entry {
    int prim = 0, i0 = 0, j0 = 0, ncol = 0, nrow = 0;
  };
  struct Tile {
    Block rect;
    std::vector<std::vector<Entry>> chunks;
    std::vector<std::uint32_t> zbuf;  // w, id per pixel, row-major
  };
  const int tw = std::min(b.w, Z_PIXELS);
  const int th = std::max(1, std::min(b.h, Z_PIXELS / std::max(tw, 1)));
  std::vector<Tile> tiles;
  for (int y = b.y0; y < b.y0 + b.h; y += th)
    for (int x = b.x0; x < b.x0 + b.w; x += tw) {
      Tile t;
      t.rect = Block{x, y, std::min(tw, b.x0 + b.w - x), std::min(th, b.y0 + b.h - y)};
      std::vector<Entry> chunk;
      for (int prim : triangles) {
        cost.list_elements += 1;
        const ScreenRect& r = prim_rect_.at(prim);
        if (!r.overlaps(t.rect)) continue;
        Entry e{prim, t.rect.x0, t.rect.y0, t.rect.x0 + t.rect.w - 1, t.rect.y0 + t.rect.h - 1};
        if (r.status == ScreenRect::kBounded) {  // clip r_box's rectangle to the tile
          e.i0 = std::max(e.i0, r.i0);
          e.j0 = std::max(e.j0, r.j0);
          e.ncol = std::min(e.ncol, r.i1);
          e.nrow = std::min(e.nrow, r.j1);
        }
        e.ncol = e.ncol - e.i0 + 1;
        e.nrow = e.nrow - e.j0 + 1;
        chunk.push_back(e);
        if (static_cast<int>(chunk.size()) == kPrimSlots) t.chunks.push_back(std::move(chunk)), chunk.clear();
      }
      if (!chunk.empty()) t.chunks.push_back(std::move(chunk));
      t.zbuf.resize(2 * static_cast<std::size_t>(t.rect.w) * t.rect.h);
      for (std::size_t p = 0; p < t.zbuf.size(); p += 2) t.zbuf[p] = 0, t.zbuf[p + 1] = kNoHit;
      tiles.push_back(std::move(t));
    }
  std::size_t levels = 0;
  for (const auto& t : tiles) levels = std::max(levels, t.chunks.size());
  for (std::size_t c = 0; c < levels; ++c) {
    std::vector<int> items;
    for (int k = 0; k < static_cast<int>(tiles.size()); ++k)
      if (tiles[k].chunks.size() > c) items.push_back(k);
    auto fill = [&](int item) {
      Tile& t = tiles[items[item]];
      const auto& chunk = t.chunks[c];
      ensure_scene(step);
      std::vector<int> prims;
      for (const auto& e : chunk) prims.push_back(e.prim);
      const auto slots = place_prims(prims, step);
      std::vector<std::uint32_t> words;
      for (std::size_t k = 0; k < chunk.size(); ++k) {
        const Entry& e = chunk[k];
        const int addr = ZBUF + 2 * ((e.j0 - t.rect.y0) * t.rect.w + (e.i0 - t.rect.x0));
        for (int v : {slots[k], e.i0, e.j0, e.ncol, e.nrow, addr}) words.push_back(static_cast<std::uint32_t>(v));
      }
      write(Z_LIST, words.data(), words.size(), step);
      if (c > 0) write(ZBUF, t.zbuf.data(), t.zbuf.size(), step);
      const std::uint32_t head[4] = {static_cast<std::uint32_t>(chunk.size()), c > 0 ? 1u : 0u,
                                     static_cast<std::uint32_t>(2 * t.rect.w),
                                     static_cast<std::uint32_t>(t.rect.w * t.rect.h)};
      write(H_MODE, head + 1, 3, step);
      write(COUNT, head, 1, step);
    };
    auto drain = [&](int item) {
      Tile& t = tiles[items[item]];
      t.zbuf = read(ZBUF, t.zbuf.size(), step);
    };
    stream("r_scan", static_cast<int>(items.size()), step, fill, drain);
  }
  std::vector<ZEntry> z(static_cast<std::size_t>(b.w) * b.h);
  for (const auto& t : tiles)
    for (int j = 0; j < t.rect.h; ++j)
      for (int i = 0; i < t.rect.w; ++i) {
        const std::size_t from = 2 * (static_cast<std::size_t>(j) * t.rect.w + i);
        z[static_cast<std::size_t>(t.rect.y0 - b.y0 + j) * b.w + (t.rect.x0 - b.x0 + i)] =
            ZEntry{t.zbuf[from], t.zbuf[from + 1]};
      }
  return z;
}

// ---------------------------------------------------------------- s1: r_surf

namespace {
constexpr std::uint32_t kOne = 0x3F0000;  // FP24 1.0
bool is_hit(const RenderFirmware::Ray& r) { return r.rec[R_ID] != kNoHit; }
}  // namespace

void RenderFirmware::surface(std::vector<Ray>& rays, Step step) {
  std::vector<int> hits;
  for (int i = 0; i < static_cast<int>(rays.size()); ++i)
    if (is_hit(rays[i])) hits.push_back(i);
  const int items = (static_cast<int>(hits.size()) + kRaysPerBatch - 1) / kRaysPerBatch;
  auto fill = [&](int item) {
    ensure_scene(step);
    const int first = item * kRaysPerBatch;
    const int n = std::min(kRaysPerBatch, static_cast<int>(hits.size()) - first);
    std::vector<int> prims;
    for (int j = 0; j < n; ++j) {
      const int id = static_cast<int>(rays[hits[first + j]].rec[R_ID]);
      if (std::find(prims.begin(), prims.end(), id) == prims.end()) prims.push_back(id);
    }
    const auto slots = place_prims(prims, step);
    for (int j = 0; j < n; ++j) {
      auto rec = rays[hits[first + j]].rec;
      const int id = static_cast<int>(rec[R_ID]);
      rec[R_SLOT] = static_cast<std::uint32_t>(slots[std::find(prims.begin(), prims.end(), id) - prims.begin()]);
      write(static_cast<std::uint16_t>(RAYS + R_SIZE * j), rec.data(), R_SLOT + 1, step);
    }
    const std::uint32_t count = static_cast<std::uint32_t>(n);
    write(COUNT, &count, 1, step);
  };
  auto drain = [&](int item) {
    const int first = item * kRaysPerBatch;
    const int n = std::min(kRaysPerBatch, static_cast<int>(hits.size()) - first);
    for (int j = 0; j < n; ++j) {
      auto& rec = rays[hits[first + j]].rec;
      const auto back = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j + R_P), R_INSIDE - R_P + 1, step);
      std::copy(back.begin(), back.end(), rec.begin() + R_P);
      rec[R_SOLID] = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j + R_SOLID), 1, step)[0];
    }
  };
  stream("r_surf", items, step, fill, drain);
}

// ---------------------------------------------------------------- s2: shadow rays

// fig. 6's shadow list of (object A, light L), narrowed to these rays: a
// shadow ray from a hit point p of A stays in box(hits on A u {L}) = H, so a
// triangle of `candidates` whose padded view box (r_box) misses H cannot
// block it. MPU work: FP24 order keys compared as integers.
std::vector<int> RenderFirmware::narrow_shadow_list(const std::vector<int>& candidates, int light,
                                                    const Box& hits) {
  Box h = hits;
  for (int c = 0; c < 3; ++c) {
    const std::int32_t l = order_key(view_.lights[light][L_POS + c]);
    h[c] = std::min(h[c], l);
    h[3 + c] = std::max(h[3 + c], l);
  }
  std::vector<int> out;
  for (int q : candidates) {
    const std::uint32_t type = view_.prims[q][P_TYPE];
    if (type == kTriangle || type == kPseudoTriangle) {
      const Box& p = prim_box_[q];
      if (p[0] > h[3] || p[1] > h[4] || p[2] > h[5] || p[3] < h[0] || p[4] < h[1] || p[5] < h[2]) continue;
    }
    out.push_back(q);
  }
  stats_.step[static_cast<int>(Step::Shadows)].list_elements += candidates.size();
  return out;
}

std::vector<int> RenderFirmware::shadow_candidates(int object, int light, const Box& hits) {
  std::vector<int> all;
  for (int b : shadow_list(object, light)) {
    const auto& obj = view_.objects[b];
    for (int q = obj.first_prim; q < obj.first_prim + obj.prim_count; ++q) all.push_back(q);
  }
  return narrow_shadow_list(all, light, hits);
}

RenderFirmware::Ray RenderFirmware::shadow_ray(const Ray& hit, int light) {
  Ray s;
  std::copy(hit.rec.begin() + R_P, hit.rec.begin() + R_P + 3, s.rec.begin() + R_O);
  s.rec[R_KIND] = 1;
  s.rec[R_ARG] = static_cast<std::uint32_t>(light);
  s.rec[R_ID] = kNoHit;
  s.from = static_cast<int>(hit.rec[R_ID]);
  return s;
}

void RenderFirmware::shadows(std::vector<Ray>& rays) {
  const int lights = static_cast<int>(view_.lights.size());
  // Hits in groups of half an r_cast batch of shadow rays (a group's rays
  // toward every light); the box of the hit points (FP24 order keys) on each
  // object, per group and for the whole generation. Teapot 64x48 on 4 NCs,
  // s2 APU cycles by hits per group: 105 M (16), 91 M (8), 87 M (4), 259 M
  // with the generation's box alone; smaller groups cost the MPU more lists.
  const int group_size = std::max(1, kRaysPerBatch / (2 * std::max(lights, 1)));
  std::map<std::pair<int, int>, Box> group_box;  // (group, object)
  std::map<int, Box> hit_box;                    // object
  auto grow = [](auto& boxes, const auto& key, const Box& p) { grow_box(boxes.emplace(key, kEmptyBox).first->second, p); };
  std::vector<int> group_of(rays.size(), -1);
  int hit_count = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    if (!is_hit(r)) continue;
    const int o = view_.prim_object.at(r.rec[R_ID]);
    Box p;
    for (int c = 0; c < 3; ++c) p[c] = p[3 + c] = order_key(r.rec[R_P + c]);
    group_of[i] = hit_count++ / group_size;
    grow(hit_box, o, p);
    grow(group_box, std::make_pair(group_of[i], o), p);
  }
  // Two levels: fig. 6's list narrowed to the generation's hits on the
  // object, then to the group's (a subset of the first: the MPU scans the
  // short list once per group).
  std::map<std::pair<int, int>, std::vector<int>> block_list;  // (object, light)
  for (const auto& [o, box] : hit_box)
    for (int l = 0; l < lights; ++l) block_list[{o, l}] = shadow_candidates(o, l, box);
  std::vector<std::vector<int>> lists;
  std::map<std::pair<int, int>, int> list_of;  // (group, object * lights + light) -> index in lists
  for (const auto& [key, box] : group_box)
    for (int l = 0; l < lights; ++l) {
      list_of[{key.first, key.second * lights + l}] = static_cast<int>(lists.size());
      lists.push_back(narrow_shadow_list(block_list.at({key.second, l}), l, box));
    }
  std::vector<Ray> probes;
  std::vector<std::pair<int, int>> owner;  // (ray, light)
  for (int i = 0; i < static_cast<int>(rays.size()); ++i) {
    rays[i].rec[R_SHADOW] = 0;
    if (!is_hit(rays[i])) continue;
    for (int l = 0; l < lights; ++l) {
      Ray s = shadow_ray(rays[i], l);
      s.list = list_of.at({group_of[i], view_.prim_object.at(s.from) * lights + l});
      probes.push_back(s);
      owner.emplace_back(i, l);
    }
  }
  stats_.shadow_rays += probes.size();
  cast(probes, lists, Step::Shadows);
  for (std::size_t k = 0; k < probes.size(); ++k)
    if (is_hit(probes[k])) rays[owner[k].first].rec[R_SHADOW] |= 1u << owner[k].second;
  stats_.step[static_cast<int>(Step::Shadows)].list_elements += probes.size();
}

// ---------------------------------------------------------------- the solid rule: r_inside

// Per object, the region primitives (ellipsoids, quadrics) against which a
// hit on one of its primitives must be tested: a solid with at least one
// region and another primitive (docs/scene-format.md: only regions hide).
void RenderFirmware::build_solid_regions() {
  solid_regions_.assign(view_.objects.size(), {});
  for (std::size_t o = 0; o < view_.objects.size(); ++o) {
    const auto& obj = view_.objects[o];
    if (!obj.solid || obj.prim_count < 2) continue;
    std::vector<int> regions;
    for (int k = 0; k < obj.prim_count; ++k) {
      const std::uint32_t type = view_.prims.at(obj.first_prim + k)[P_TYPE];
      if (type == kEllipsoid || type == kQuadric) regions.push_back(obj.first_prim + k);
    }
    stats_.step[static_cast<int>(Step::Transform)].list_elements += obj.prim_count;
    solid_regions_[o] = std::move(regions);
  }
}

// A hit that another region of its solid may hold (not a shadow ray).
bool RenderFirmware::may_be_hidden(const Ray& r) const {
  const std::uint32_t kind = r.rec[R_KIND], id = r.rec[R_ID];
  if (id == kNoHit || kind == 1 || kind == 4) return false;
  const auto& regions = solid_regions_.at(view_.prim_object.at(id));
  return regions.size() >= 2 || (regions.size() == 1 && regions[0] != static_cast<int>(id));
}

std::vector<int> RenderFirmware::hidden_hits(std::vector<Ray>& rays, const std::vector<int>& which, Step step) {
  constexpr int kListWords = 48;
  auto& cost = stats_.step[static_cast<int>(step)];
  // Batches of at most 32 rays whose hits lie on at most 8 objects; the
  // objects' regions in chunks of 48 slots (a later chunk skips rays already
  // found hidden), as in cast(). A batch without regions does not run.
  auto object_of = [&](int k) { return view_.prim_object.at(rays[which[k]].rec[R_ID]); };
  const std::vector<BatchPlan> plans = plan_batches(
      static_cast<int>(which.size()), object_of,
      [&](int o) -> const std::vector<int>& { return solid_regions_[o]; }, false, cost);
  std::vector<char> hidden(which.size(), 0);
  auto fill = [&](const BatchPlan& p, std::size_t c, const std::vector<int>& slots) {
    const auto& chunk = p.chunks[c];
    std::vector<std::uint32_t> list_words(kListWords);
    std::vector<int> list_n(p.keys.size());
    for (std::size_t k = 0; k < p.keys.size(); ++k) {
      int n = 0;
      for (std::size_t s = 0; s < chunk.size(); ++s)
        if (view_.prim_object[chunk[s]] == p.keys[k]) list_words[n++] = static_cast<std::uint32_t>(slots[s]);
      cost.list_elements += chunk.size();
      list_n[k] = n;
      if (n) write(static_cast<std::uint16_t>(LISTS + kListWords * k), list_words.data(), n, step);
    }
    for (int j = 0; j < p.n; ++j) {
      auto rec = rays[which[p.first + j]].rec;
      const int k = static_cast<int>(std::find(p.keys.begin(), p.keys.end(), object_of(p.first + j)) -
                                     p.keys.begin());
      rec[R_LIST] = static_cast<std::uint32_t>(LISTS + kListWords * k);
      rec[R_LISTN] = hidden[p.first + j] ? 0 : static_cast<std::uint32_t>(list_n[k]);
      write(static_cast<std::uint16_t>(RAYS + R_SIZE * j), rec.data(), R_LISTN + 1, step);
    }
    const std::uint32_t count = static_cast<std::uint32_t>(p.n);
    write(COUNT, &count, 1, step);
  };
  auto drain = [&](const BatchPlan& p) {
    for (int j = 0; j < p.n; ++j) {
      const std::uint32_t tmin = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j + R_TMIN), 1, step)[0];
      if (tmin == 0) continue;
      hidden[p.first + j] = 1;
      rays[which[p.first + j]].rec[R_TMIN] = tmin;
    }
  };
  stream_chunks("r_inside", plans, step, fill, drain);
  std::vector<int> out;
  for (std::size_t k = 0; k < which.size(); ++k)
    if (hidden[k]) out.push_back(which[k]);
  return out;
}

void RenderFirmware::solid_rule(std::vector<Ray>& rays, const std::vector<std::vector<int>>& lists, Step step) {
  auto& cost = stats_.step[static_cast<int>(step)];
  std::vector<int> pending;
  for (int i = 0; i < static_cast<int>(rays.size()); ++i)
    if (may_be_hidden(rays[i])) pending.push_back(i);
  cost.list_elements += rays.size();
  const std::uint32_t big = scene_words_[C_BIG - C_D0];
  // Every round moves each pending ray past one more crossing of its list's
  // primitives (at most two each): a bound that cannot be reached.
  std::size_t rounds = 0, bound = 2;
  for (const auto& l : lists) bound = std::max(bound, 2 * l.size() + 2);
  while (!pending.empty()) {
    if (++rounds > bound) throw std::logic_error("solid_rule: no end");
    const std::vector<int> hidden = hidden_hits(rays, pending, step);
    stats_.hidden_hits += hidden.size();
    if (hidden.empty()) break;
    // Cast again from the same origin and direction (an eye ray as a given
    // ray: r_cast wrote its O and D back), ignoring t <= R_TMIN.
    std::vector<Ray> again;
    for (int k : hidden) {
      Ray r = rays[k];
      r.rec[R_T] = big;
      r.rec[R_ID] = kNoHit;
      if (r.rec[R_KIND] == 2 || r.rec[R_KIND] == 5) r.rec[R_KIND] = 3;  // eye rays: as given rays
      again.push_back(r);
    }
    cast(again, lists, step);
    pending.clear();
    for (std::size_t k = 0; k < hidden.size(); ++k) {
      auto& rec = rays[hidden[k]].rec;
      for (int w = R_O; w <= R_T; ++w) rec[w] = again[k].rec[w];
      rec[R_ID] = again[k].rec[R_ID];
      rec[R_SLOT] = again[k].rec[R_SLOT];
      if (may_be_hidden(rays[hidden[k]])) pending.push_back(hidden[k]);
    }
    cost.list_elements += hidden.size();
  }
}

// ---------------------------------------------------------------- s3/s4: r_shade

void RenderFirmware::shade(std::vector<Ray>& rays, Step step) {
  const int items = (static_cast<int>(rays.size()) + kRaysPerBatch - 1) / kRaysPerBatch;
  auto fill = [&](int item) {
    ensure_scene(step);
    const int first = item * kRaysPerBatch;
    const int n = std::min(kRaysPerBatch, static_cast<int>(rays.size()) - first);
    for (int j = 0; j < n; ++j)
      write(static_cast<std::uint16_t>(RAYS + R_SIZE * j), rays[first + j].rec.data(), R_SIZE, step);
    const std::uint32_t count = static_cast<std::uint32_t>(n);
    write(COUNT, &count, 1, step);
  };
  auto drain = [&](int item) {
    const int first = item * kRaysPerBatch;
    const int n = std::min(kRaysPerBatch, static_cast<int>(rays.size()) - first);
    for (int j = 0; j < n; ++j) {
      const auto back = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j + R_OUT), R_TW + 3 - R_OUT, step);
      std::copy(back.begin(), back.end(), rays[first + j].rec.begin() + R_OUT);
    }
  };
  stream("r_shade", items, step, fill, drain);
}

// ---------------------------------------------------------------- output: r_sum

std::vector<Rgb8> RenderFirmware::sum(const std::vector<std::vector<std::array<std::uint32_t, 3>>>& contrib) {
  constexpr Step step = Step::Output;
  constexpr int kPixels = 64;
  constexpr int kPool = (4096 - POOL) / 3;
  struct Batch {
    int first = 0, n = 0;
  };
  std::vector<Batch> batches;
  for (int p = 0; p < static_cast<int>(contrib.size());) {
    Batch b{p, 0};
    int pool = 0;
    while (p < static_cast<int>(contrib.size()) && b.n < kPixels &&
           (b.n == 0 || pool + static_cast<int>(contrib[p].size()) <= kPool)) {
      if (static_cast<int>(contrib[p].size()) > kPool) throw std::runtime_error("r_sum: too many rays for a pixel");
      pool += static_cast<int>(contrib[p].size());
      ++b.n;
      ++p;
    }
    batches.push_back(b);
  }
  std::vector<Rgb8> out(contrib.size());
  auto fill = [&](int item) {
    const Batch& b = batches[item];
    std::vector<std::uint32_t> pix(2 * b.n), pool;
    for (int k = 0; k < b.n; ++k) {
      pix[2 * k] = static_cast<std::uint32_t>(POOL + pool.size());
      pix[2 * k + 1] = static_cast<std::uint32_t>(contrib[b.first + k].size());
      for (const auto& c : contrib[b.first + k]) pool.insert(pool.end(), c.begin(), c.end());
    }
    write(PIX, pix.data(), pix.size(), step);
    if (!pool.empty()) write(POOL, pool.data(), pool.size(), step);
    const std::uint32_t count = static_cast<std::uint32_t>(b.n);
    write(COUNT, &count, 1, step);
  };
  auto drain = [&](int item) {
    const Batch& b = batches[item];
    const auto v = read(OUT, 3 * b.n, step);
    for (int k = 0; k < b.n; ++k)
      out[b.first + k] = Rgb8{static_cast<std::uint8_t>(v[3 * k]), static_cast<std::uint8_t>(v[3 * k + 1]),
                              static_cast<std::uint8_t>(v[3 * k + 2])};
  };
  stream("r_sum", static_cast<int>(batches.size()), step, fill, drain);
  return out;
}

// ---------------------------------------------------------------- step 3 per block

std::vector<int> RenderFirmware::eye_candidates(const BlockList& list) {
  std::vector<int> prims;
  for (int o : list.objects) {
    const auto& obj = view_.objects.at(o);
    stats_.step[static_cast<int>(Step::HiddenSurface)].list_elements += obj.prim_count;
    // Within an object of the block list, a triangle whose own projection
    // (r_box) misses the block cannot be met by the block's eye rays.
    for (int k = 0; k < obj.prim_count; ++k)
      if (prim_rect_.at(obj.first_prim + k).overlaps(list.block)) prims.push_back(obj.first_prim + k);
  }
  return prims;
}

std::vector<RenderFirmware::Ray> RenderFirmware::hidden_surface(const BlockList& list) {
  const Block& b = list.block;
  lists_.at(0) = eye_candidates(list);  // [1] and the shadow lists are the frame's
  std::vector<int> triangles;
  std::vector<std::vector<int>> regions(1);  // the eye rays' r_cast candidates
  for (int prim : lists_[0]) {
    const std::uint32_t type = view_.prims[prim][P_TYPE];
    (type == kTriangle || type == kPseudoTriangle ? triangles : regions[0]).push_back(prim);
  }
  const std::vector<ZEntry> z = scan_convert(b, triangles);
  std::vector<Ray> gen;
  for (int j = 0; j < b.h; ++j)
    for (int i = 0; i < b.w; ++i) {
      Ray r;
      r.pixel = j * b.w + i;
      r.rec[R_KIND] = 5;
      r.rec[R_ARG] = static_cast<std::uint32_t>(b.x0 + i);
      r.rec[R_ARG2] = static_cast<std::uint32_t>(b.y0 + j);
      r.rec[R_T] = z[r.pixel].w;
      r.rec[R_ID] = z[r.pixel].id;
      r.rec[R_W] = r.rec[R_W + 1] = r.rec[R_W + 2] = kOne;
      r.rec[R_CHILD] = view_.max_depth > 0 ? 3 : 0;
      r.list = 0;
      gen.push_back(r);
    }
  cast(gen, regions, Step::HiddenSurface);
  return gen;
}

// s4's candidates, one list per ray: every primitive in file order, as the
// paper's s4 has no lists, less the triangles that lie wholly behind the
// ray. A ray with d_c >= 0 (sign bit clear) never reaches a point with x_c
// below its origin's, so a triangle whose padded view box (r_box, 16
// epsilon) ends below it cannot be hit; the same for d_c < 0 and a box that
// begins above it. An object whose triangles' box is behind is passed over
// whole. Regions are kept. MPU work: order keys and sign bits compared as
// integers. Teapot 64x48 on 4 NCs, s4 APU cycles: 98 M with no culling,
// 11 M with a list per ray (an r_cast batch then holds 8 rays, not 32);
// lists shared by groups of 2 or 4 consecutive rays (culling on the axes
// where all agree) gave 19 M and 30 M.
void RenderFirmware::secondary_candidates(std::vector<Ray>& rays, std::vector<std::vector<int>>& lists) {
  auto& cost = stats_.step[static_cast<int>(Step::Secondary)];
  for (Ray& r : rays) {
    std::array<std::int32_t, 3> origin;
    unsigned negative = 0;  // bit c: d_c's sign bit
    for (int c = 0; c < 3; ++c) {
      origin[c] = order_key(r.rec[R_O + c]);
      negative |= ((r.rec[R_D + c] >> 23) & 1u) << c;
    }
    auto behind = [&](const Box& b) {
      for (int c = 0; c < 3; ++c)
        if ((negative >> c) & 1 ? b[c] > origin[c] : b[3 + c] < origin[c]) return true;
      return false;
    };
    std::vector<int> list;
    for (std::size_t o = 0; o < view_.objects.size(); ++o) {
      const auto& obj = view_.objects[o];
      const bool skip_triangles = behind(object_tri_box_[o]);
      cost.list_elements += skip_triangles ? 1 : obj.prim_count;
      for (int q = obj.first_prim; q < obj.first_prim + obj.prim_count; ++q) {
        const std::uint32_t type = view_.prims[q][P_TYPE];
        if ((type == kTriangle || type == kPseudoTriangle) && (skip_triangles || behind(prim_box_[q]))) continue;
        list.push_back(q);
      }
    }
    r.list = static_cast<int>(lists.size());
    lists.push_back(std::move(list));
  }
}

std::vector<RenderFirmware::Ray> RenderFirmware::children(const std::vector<Ray>& gen, int depth) const {
  const std::uint32_t big = scene_words_[C_BIG - C_D0];
  std::vector<Ray> next;
  for (const auto& r : gen)
    for (int c = 0; c < 2; ++c) {
      if (!(r.rec[R_CHILD] & (1u << c))) continue;
      Ray k;
      const int dir = c == 0 ? R_RD : R_TD, w = c == 0 ? R_RW : R_TW;
      std::copy(r.rec.begin() + R_P, r.rec.begin() + R_P + 3, k.rec.begin() + R_O);
      std::copy(r.rec.begin() + dir, r.rec.begin() + dir + 3, k.rec.begin() + R_D);
      std::copy(r.rec.begin() + w, r.rec.begin() + w + 3, k.rec.begin() + R_W);
      k.rec[R_T] = big;
      k.rec[R_ID] = kNoHit;
      k.rec[R_KIND] = 0;
      k.rec[R_CHILD] = depth + 1 < view_.max_depth ? 3 : 0;
      k.pixel = r.pixel;
      k.depth = depth + 1;
      k.from = static_cast<int>(r.rec[R_ID]);
      k.list = 1;
      next.push_back(k);
    }
  return next;
}

std::vector<Rgb8> RenderFirmware::render_block(const BlockList& list) {
  std::vector<Ray> gen = hidden_surface(list);
  std::vector<std::vector<std::array<std::uint32_t, 3>>> contrib(gen.size());
  stats_.rays += gen.size();
  for (int depth = 0; !gen.empty(); ++depth) {
    const Step s1 = depth == 0 ? Step::HiddenSurface : Step::Secondary;
    const Step s3 = depth == 0 ? Step::Shading : Step::Secondary;
    std::vector<std::vector<int>> own;  // secondary rays: one list each
    if (depth > 0) {                     // depth 0: hidden_surface did s1
      secondary_candidates(gen, own);
      cast(gen, own, s1);
    }
    solid_rule(gen, depth == 0 ? lists_ : own, s1);  // eye rays: list 0
    surface(gen, s1);
    shadows(gen);
    shade(gen, s3);
    for (const auto& r : gen) contrib[r.pixel].push_back({r.rec[R_OUT], r.rec[R_OUT + 1], r.rec[R_OUT + 2]});
    std::vector<Ray> next = children(gen, depth);
    stats_.secondary_rays += next.size();
    stats_.step[static_cast<int>(s3)].list_elements += gen.size();
    gen = std::move(next);
  }
  return sum(contrib);
}

}  // namespace mc1::render
