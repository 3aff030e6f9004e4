// The renderer's MPU firmware (paper section 4, fig. 3): integer work, lists,
// transfers, bank swaps and control around the APU kernels r_*.apu, which do
// every floating-point operation of the frame in FP24. Independent of
// SystemC: it reaches the APU only through an ApuLink (ApuDriver plus the
// NC's notion of waiting), so the same code runs standalone on the ISS and
// inside the platform's node computer. docs/renderer.md describes the data
// layouts and the steps; render_fw.cpp lists the files of the steps.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "apu_driver.hpp"
#include "apu_engine.hpp"
#include "scene_image.hpp"

namespace mc1::render {

// What the firmware needs of its node computer. The platform implements it
// on its NcPort (apu_wait_swap, apu_wait_halt, copy_words, ...); DirectLink
// clocks the APU itself.
class ApuLink {
 public:
  virtual ~ApuLink() = default;
  virtual apu::ApuDriver& apu() = 0;
  virtual void wait_swap() = 0;  // until the APU took the handed-over data bank
  virtual void wait_halt() = 0;  // until HALT; throws on a fault
  // MPU work, by the classes of the platform's timing table.
  virtual void copy_words(std::uint64_t) {}
  virtual void list_elements(std::uint64_t) {}
  virtual void sort_compares(std::uint64_t) {}
  virtual void apu_commands(std::uint64_t) {}
  // The firmware starts work of another step of fig. 3 (step_name()), for
  // the activity chart; costs no time.
  virtual void enter_step(const char* /*name*/) {}
  // What the firmware does, for the NC's waveform and stall profile
  // (nc::NcPort::mpu_activity): `code` activity_code(step), `detail` the
  // batch of the step's stream in hand (0 outside one); costs no time.
  virtual void activity(std::uint16_t /*code*/, std::uint32_t /*detail*/) {}
};

// Standalone: the MPU is infinitely fast; waiting clocks the APU.
class DirectLink final : public ApuLink {
 public:
  explicit DirectLink(apu::ApuDriver& drv, std::uint64_t max_cycles = 2'000'000'000ull)
      : drv_(drv), max_cycles_(max_cycles) {}
  apu::ApuDriver& apu() override { return drv_; }
  void wait_swap() override;
  void wait_halt() override;

 private:
  apu::ApuDriver& drv_;
  std::uint64_t max_cycles_;
};

// APU and MPU work of one step of the frame algorithm.
struct StepCost {
  std::uint64_t apu_cycles = 0;   // start() to HALT, stalls included, settle cycles not
  std::uint64_t apu_runs = 0;     // kernel runs (start .. HALT)
  std::uint64_t batches = 0;      // data banks handed over
  std::uint64_t word_copies = 0;  // MPU <-> APU bank words (program words count 8)
  std::uint64_t list_elements = 0;
  std::uint64_t sort_compares = 0;
  std::uint64_t apu_commands = 0;  // hand-overs and starts
  // The engine's counters (apu::ApuCounters): words issued, and cycles the
  // APU waited at SWAPD for the MPU's data bank.
  std::uint64_t apu_issued = 0, apu_bank_stalls = 0;
  StepCost& operator+=(const StepCost& o);
};

// APU work of one kernel over the frame (docs/renderer.md "Timing"): start()
// to HALT; issues, stalls and unit ops from the engine's counters, as StepCost's.
struct KernelCost {
  std::uint64_t apu_cycles = 0, apu_runs = 0, batches = 0;
  std::uint64_t apu_issued = 0, apu_bank_stalls = 0;
  std::uint64_t apu_dependence_stalls = 0;  // RAW, WAW, CC and drain stalls
  std::array<std::uint64_t, 3> unit_ops{};   // multiplier, adder, function unit
  KernelCost& operator+=(const KernelCost& o);
};

enum class Step { Transform, BlockLists, HiddenSurface, Shadows, Shading, Secondary, Output };
constexpr int kSteps = 7;
const char* step_name(Step s);
// The firmware's activity codes (ApuLink::activity): a step's is its index + 1, named step_name().
constexpr std::uint16_t activity_code(Step s) { return static_cast<std::uint16_t>(static_cast<int>(s) + 1); }

struct RenderStats {
  std::array<StepCost, kSteps> step{};
  std::uint64_t rays = 0, shadow_rays = 0, secondary_rays = 0;
  std::uint64_t hidden_hits = 0;  // solid rule: hits found inside a sibling region (each re-cast once)
  std::map<std::string, KernelCost> kernels;  // by kernel name (r_cast, ...)
  StepCost total() const;
};

struct Block {
  int x0 = 0, y0 = 0, w = 0, h = 0;  // pixels [x0, x0 + w) x [y0, y0 + h)
};

// s2 of fig. 3: the objects whose projected box overlaps a block, nearest
// first (by the FP24 nearest z of the box, compared as integers).
struct BlockList {
  Block block;
  std::vector<int> objects;
  std::uint32_t load = 0;  // the RC's load prediction: objects, reflecting ones counted 4x
};

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8& o) const { return r == o.r && g == o.g && b == o.b; }
};

// An FP24 number as an integer that orders like the number (both zeros 0).
std::int32_t order_key(std::uint32_t fp24);

// Kernel images by name (r_xform, r_box, ...), as the RC broadcasts them.
using KernelTable = std::map<std::string, std::vector<apu::Encoded>>;

class RenderFirmware {
 public:
  explicit RenderFirmware(ApuLink& link);
  explicit RenderFirmware(apu::ApuDriver& drv);  // with its own DirectLink

  // Run these kernel images (an NC: the ones the RC broadcast) instead of
  // the firmware library's own copy (kernel_words). A kernel the table lacks
  // is an error (std::runtime_error naming it) when a step first needs it.
  void use_kernels(KernelTable table);

  // Step 1 (fig. 3): the broadcast scene to view coordinates on the APU
  // (r_xform), with the eye-ray constants and each object's view box.
  void load_scene(const SceneImage& image);
  // Or the product of step 1 directly (tests; a scene already in view
  // coordinates).
  void load_view_scene(const ViewScene& view);
  const ViewScene& view() const { return view_; }

  // Step 2: project the object boxes (r_box) and list the objects that may
  // appear in `block`, nearest first.
  BlockList build_block_list(const Block& block);
  // s1's candidates for the block's eye rays: the primitives of the block
  // list's objects, nearest object first, less the triangles whose own
  // projection misses the block.
  std::vector<int> eye_candidates(const BlockList& list);
  // fig. 6: the objects that may block `light` for the points of `object`
  // (r_slist on the view boxes), in file order. Made when first needed
  // (ensure_shadow_lists): the MPU passes r_slist only the objects whose box
  // may meet the padded box of the object and the light.
  const std::vector<int>& shadow_list(int object, int light) {
    ensure_shadow_lists({{object, light}});
    return shadow_objects_.at(static_cast<std::size_t>(object) * view_.lights.size() + light);
  }
  // The same lists by r_slist over every (object, light, object) (the
  // method before issue 39), [object * lights + light]: for tests. Its
  // work is booked to s2 like any other.
  std::vector<std::vector<int>> exhaustive_shadow_lists();
  // Step 3, s1..s4 for one block: RGB8 pixels, row-major.
  std::vector<Rgb8> render_block(const BlockList& list);
  // Tells the link (ApuLink::enter_step) that work of step `s` begins, if
  // it is not the step under way; the NC firmware's pixel output uses it.
  void enter_step(Step s) {
    if (step_ == static_cast<int>(s)) return;
    step_ = static_cast<int>(s);
    link_.enter_step(step_name(s));
    link_.activity(activity_code(s), 0);
  }

  // s1's Z-buffer for triangles (r_scan): per pixel of `block`, row-major,
  // the w word (1 / distance along the pixel's unnormalised eye direction)
  // and the P_ID (kNoHit: none) of the nearest of `triangles` (scan
  // conversion of each over its projected rectangle; ties keep the earlier
  // entry).
  struct ZEntry {
    std::uint32_t w = 0, id = kNoHit;
  };
  std::vector<ZEntry> scan_convert(const Block& block, const std::vector<int>& triangles);

  const RenderStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }
  // Another program used the APU: forget what the banks hold.
  void invalidate_banks();

  // One ray as the MPU keeps it: the R_SIZE-word record of r_layout.inc
  // plus integer bookkeeping.
  struct Ray {
    std::array<std::uint32_t, layout::R_SIZE> rec{};
    int list = 0;    // candidate list (index into the lists it is cast with)
    int pixel = 0;   // index in the block
    int depth = 0;   // 0: eye ray
    int from = -1;   // primitive the ray leaves (R_FROM): shadow and secondary rays
    std::uint32_t limit = 0;  // the solid rule's re-cast: t limit (0: C_BIG); a shadow ray's to its light
  };
  // s1's eye rays of a block, row-major, with their nearest hits: r_scan's
  // Z-buffer over the block's triangles, then r_cast (RK_EYE_SCAN) against its
  // ellipsoids and quadrics (per-pixel ray-surface intersection).
  std::vector<Ray> hidden_surface(const BlockList& list);
  // s1/s2/s4 intersection pass over `rays` (r_cast); public for tests.
  void cast(std::vector<Ray>& rays, const std::vector<std::vector<int>>& lists, Step step);
  // The solid rule (docs/scene-format.md "Objects"), after a cast of eye or
  // secondary rays: a hit on a primitive of a solid that lies strictly
  // inside another region primitive of that solid (r_inside) is not on the
  // solid's boundary; the ray is cast again (against lists[ray.list]) past
  // it, ignoring t <= the hidden hit's t (R_TMIN), until its hit is visible
  // or it has none. Shadow rays (RK_SHADOW*) are left alone: the reference's
  // s2 counts every crossing. R_TMIN of a ray that went on keeps the t of its
  // last hidden hit.
  void solid_rule(std::vector<Ray>& rays, const std::vector<std::vector<int>>& lists, Step step);
  // s1 (r_surf): hit point, shading normal, material, colour of every hit.
  void surface(std::vector<Ray>& rays, Step step);
  // s2: shadow rays to every light (r_cast), R_SHADOW bits.
  void shadows(std::vector<Ray>& rays);
  // The shadow ray (RK_SHADOW) from a hit's point toward `light`, leaving the
  // hit's primitive; its list is the caller's.
  static Ray shadow_ray(const Ray& hit, int light);
  // s3/s4 (r_shade): weighted local colour and the secondary rays' data.
  void shade(std::vector<Ray>& rays, Step step);
  // The reflected and transmitted rays of a shaded generation at `depth`
  // (list 1: every primitive).
  std::vector<Ray> children(const std::vector<Ray>& gen, int depth) const;
  // s4's candidates: appends one list per ray of `rays` to `lists` and sets
  // the ray's `list`: every primitive less the triangles behind the ray
  // (docs/renderer.md).
  void secondary_candidates(std::vector<Ray>& rays, std::vector<std::vector<int>>& lists);

 private:
  struct Bank {
    bool scene_valid = false;
    std::vector<int> slot_prim;  // primitive cached in each PRIMS slot, -1 none
  };
  using Box = std::array<std::int32_t, 6>;  // min xyz, max xyz as order_key()s
  // Every piece of work is booked to its step here, so this is also where
  // the link learns that the step changed.
  StepCost& cost(Step s) {
    enter_step(s);
    return stats_.step[static_cast<int>(s)];
  }

  // ---- bank streaming (render_stream.cpp)
  const std::vector<apu::Encoded>& kernel(const std::string& name) const;
  void use_kernel(const std::string& name, Step step);
  // The stream protocol over `items` batches: fill(i) writes batch i into the
  // MPU's bank, drain(i) reads its results back.
  using BatchFn = std::function<void(int)>;
  void stream(const std::string& kernel, int items, Step step, const BatchFn& fill, const BatchFn& drain);
  static void count_issue(const apu::ApuCounters& before, const apu::ApuCounters& after, StepCost& c,
                          KernelCost& k);
  // The stream of most kernels: `count` items in batches of at most
  // `per_batch`; item j of a batch at base + stride j. A batch is filled by
  // the scene words if `scene`, begin(first, n), put(item, address) for each
  // of its items, end(first, n) and its COUNT; drained by get(item, address)
  // for each.
  struct ItemStream {
    ItemStream(int count, int per_batch, int base, int stride, bool scene)
        : count(count), per_batch(per_batch), base(base), stride(stride), scene(scene) {}
    int count, per_batch, base, stride;
    bool scene;
    std::function<void(int, int)> begin, end;  // optional
    std::function<void(int, std::uint16_t)> put, get;
  };
  void stream_items(const std::string& kernel, Step step, const ItemStream& s);
  Bank& mpu_bank() { return banks_[mpu_bank_]; }
  void forget_bank_data();  // neither bank holds the scene or a primitive
  void write(std::uint16_t addr, const std::uint32_t* w, std::size_t n, Step step);
  void write_count(int n, Step step);  // the batch's COUNT word
  // The n words, valid until the next read().
  const std::vector<std::uint32_t>& read(std::uint16_t addr, std::size_t n, Step step);
  void ensure_scene(Step step);
  std::vector<int> place_prims(const std::vector<int>& prims, Step step);  // slots

  // ---- step 1 (render_step1.cpp)
  void xform_camera(const SceneImage& img, std::array<std::uint32_t, 9>& rot, ViewScene::Constants& cam);
  void build_triangle_boxes();  // object_tri_box_

  // ---- step 2 (render_blocklist.cpp): r_box's screen rectangle in pixel
  // indices, padded.
  struct ScreenRect {
    enum Status : int { kBounded = layout::BS_BOUNDED, kWholeScreen = layout::BS_WHOLE, kBehind = layout::BS_BEHIND };
    int status = kWholeScreen;
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    bool overlaps(const Block& b) const;
  };
  void project_boxes();  // r_box over every object box and triangle

  // ---- r_cast's and r_inside's batches (render_cast.cpp)
  struct BatchPlan {
    int first = 0, n = 0;                  // items first .. first + n - 1
    std::vector<int> keys;                 // distinct candidate lists, in first use order
    std::vector<std::vector<int>> chunks;  // the keys' primitives, <= kPrimSlots per chunk
    std::vector<std::vector<std::vector<int>>> split;  // [key][chunk]: the key's primitives' positions in it
    int key_index(int key) const;          // of a key among keys
  };
  std::vector<BatchPlan> plan_batches(int items, const std::function<int(int)>& key_of,
                                      const std::function<const std::vector<int>&(int)>& prims_of, bool always_run,
                                      StepCost& cost);
  using ChunkFill = std::function<void(const BatchPlan&, std::size_t, const std::vector<int>&)>;
  void stream_chunks(const std::string& kernel, const std::vector<BatchPlan>& plans, Step step, const ChunkFill& fill,
                     const std::function<void(const BatchPlan&)>& drain);
  static std::uint16_t list_addr(int k);  // candidate list k of a batch
  // Writes a batch's candidate lists (slots_of(k, out): list k's PRIMS
  // slots appended to out, which comes empty); returns their lengths.
  std::vector<int> write_lists(std::size_t keys,
                               const std::function<void(std::size_t, std::vector<std::uint32_t>&)>& slots_of, Step step);
  void write_plane_left(const Ray& ray, bool first_pass, std::uint16_t at, Step step);
  void fill_cast(const std::vector<Ray>& rays, const BatchPlan& p, std::size_t c, const std::vector<int>& slots,
                 Step step);

  // ---- s1 (render_s1.cpp): r_scan's tiles
  struct ScanEntry {
    int prim = 0, i0 = 0, j0 = 0, ncol = 0, nrow = 0;
  };
  struct ScanTile {
    Block rect;
    std::vector<std::vector<ScanEntry>> chunks;
    std::vector<std::uint32_t> zbuf;  // ZB_SIZE words per pixel, row-major
  };
  void clip_to_tile(ScanTile& t, const std::vector<int>& triangles);
  void fill_scan(const ScanTile& t, std::size_t c, Step step);

  // ---- the solid rule (render_solid.cpp)
  // Per object, the region primitives a hit on it must be tested against
  // (empty unless a solid with a region and another primitive).
  void build_solid_regions();
  bool may_be_hidden(const Ray& r) const;
  // r_inside over rays[which[k]]: the hits strictly inside another region of
  // their solid get R_TMIN = R_T; returns them (indices into rays).
  std::vector<int> hidden_hits(std::vector<Ray>& rays, const std::vector<int>& which, Step step);
  std::vector<int> cast_past(std::vector<Ray>& rays, const std::vector<int>& hidden,
                             const std::vector<std::vector<int>>& lists, Step step);

  // ---- s2 (render_s2.cpp)
  void build_shadow_lists();  // forgets the lists of the last scene
  // The shadow lists of these (object, light) pairs that are not made yet,
  // in one r_slist stream (the MPU's conservative box test first).
  void ensure_shadow_lists(const std::vector<std::pair<int, int>>& pairs);
  void run_slist(std::int64_t count, const std::function<std::array<int, 3>(int)>& pair_of,
                 const std::function<void(int, int, int)>& found);
  std::vector<int> shadow_candidates(int object, int light, const Box& hits);
  std::vector<int> narrow_shadow_list(const std::vector<int>& candidates, int light, const Box& hits);
  struct ShadowGroups {
    std::vector<int> group_of;  // per ray: its group of hits, -1 a miss
    std::vector<std::vector<int>> lists;
    std::map<std::pair<int, int>, int> list_of;  // (group, object * lights + light) -> index in lists
  };
  ShadowGroups shadow_groups(const std::vector<Ray>& rays);
  // The shadow probes left unblocked, cast again as given rays against the
  // intersections' and differences' regions of their lists (csg_lists), the
  // solid rule applied: a visible crossing below the limit blocks.
  void combined_shadows(std::vector<Ray>& probes, const std::vector<std::vector<int>>& csg_lists);

  // ---- output (render_output.cpp)
  std::vector<Rgb8> sum(const std::vector<std::vector<std::array<std::uint32_t, 3>>>& contrib);

  std::unique_ptr<DirectLink> own_link_;  // before link_: it may refer to it
  ApuLink& link_;
  ViewScene view_;
  std::vector<ScreenRect> object_rect_;     // per object: its view box on the screen
  std::vector<ScreenRect> prim_rect_;       // per primitive: triangles' own, regions kWholeScreen
  std::vector<Box> prim_box_;               // per triangle: its padded view box (r_box)
  std::vector<Box> object_tri_box_;         // per object: the union of its triangles' prim_box_
  std::vector<std::vector<int>> shadow_objects_;  // [object * lights + light]
  std::vector<char> shadow_known_;                // [object * lights + light]: shadow_objects_ made
  std::vector<int> shadow_holding_;               // the objects that hold a primitive, in file order
  std::vector<std::vector<int>> solid_regions_;   // [object]: build_solid_regions
  std::vector<char> prim_combined_;  // per primitive: of an intersection or difference (build_solid_regions)
  bool any_combined_ = false;        // some object is an intersection or difference
  // Candidate lists of primitives: [0] the block's eye rays (s1), [1] every
  // primitive in file order. s2 (shadows) and s4 (secondary_candidates)
  // make their own per group of rays.
  std::vector<std::vector<int>> lists_;
  std::vector<std::uint32_t> scene_words_;  // words C_D0 .. PRIMS - 1 of every bank
  std::array<Bank, 2> banks_;
  int mpu_bank_ = 0;  // which of banks_ the MPU owns (relative naming)
  std::vector<std::uint32_t> read_buf_;   // read()'s words
  std::vector<std::uint32_t> list_buf_;   // write_lists()' list
  std::vector<int> sorted_buf_;           // plan_batches()' primitives of a batch
  int step_ = -1;     // the step last told to the link (enter_step)
  std::string apu_prog_, mpu_prog_;
  std::unique_ptr<const KernelTable> kernels_;  // null: the library's copy
  RenderStats stats_;
};

}  // namespace mc1::render
