// The Download payloads of the rendered frame: the scene image and the
// kernels as the RC broadcasts them (docs/platform.md "The rendered frame").
#include <string>

#include "render_kernels.hpp"
#include "render_nc.hpp"

namespace mc1::render_nc {
namespace {

constexpr unsigned kSlabFollows = 0x80;  // a primitive's type byte: its slab words follow

class Writer {
 public:
  void u8(unsigned v) { b_.push_back(static_cast<std::uint8_t>(v)); }
  void u16(unsigned v) {
    u8(v & 0xFF);
    u8(v >> 8 & 0xFF);
  }
  void u32(std::uint32_t v) {
    u16(v & 0xFFFF);
    u16(v >> 16);
  }
  void u64(std::uint64_t v) {
    u32(static_cast<std::uint32_t>(v));
    u32(static_cast<std::uint32_t>(v >> 32));
  }
  void word(render::Word w) {  // one FP24 data word
    u8(w & 0xFF);
    u8(w >> 8 & 0xFF);
    u8(w >> 16 & 0xFF);
  }
  template <std::size_t N>
  void words(const std::array<render::Word, N>& w) {
    for (render::Word x : w) word(x);
  }
  rc::Bytes take() { return std::move(b_); }

 private:
  rc::Bytes b_;
};

class Reader {
 public:
  Reader(const rc::Bytes& b, const char* what) : b_(b), what_(what) {}
  std::uint64_t get(int bytes) {
    if (at_ + static_cast<std::size_t>(bytes) > b_.size())
      throw rc::ProtocolError(std::string(what_) + " download ends at byte " + std::to_string(b_.size()) +
                              " inside a field at byte " + std::to_string(at_));
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = v << 8 | b_[at_ + static_cast<std::size_t>(i)];
    at_ += static_cast<std::size_t>(bytes);
    return v;
  }
  unsigned u8() { return static_cast<unsigned>(get(1)); }
  unsigned u16() { return static_cast<unsigned>(get(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(get(4)); }
  std::uint64_t u64() { return get(8); }
  render::Word word() { return static_cast<render::Word>(get(3)); }
  template <std::size_t N>
  void words(std::array<render::Word, N>& w) {
    for (render::Word& x : w) x = word();
  }
  void count_check(std::uint64_t n, std::uint64_t bytes_each) const {
    if (n * bytes_each > b_.size() - at_)
      throw rc::ProtocolError(std::string(what_) + " download: " + std::to_string(n) + " records of " +
                              std::to_string(bytes_each) + " bytes in " + std::to_string(b_.size() - at_));
  }
  void end() const {
    if (at_ != b_.size())
      throw rc::ProtocolError(std::string(what_) + " download: " + std::to_string(b_.size() - at_) +
                              " bytes left over");
  }

 private:
  const rc::Bytes& b_;
  const char* what_;
  std::size_t at_ = 0;
};

}  // namespace

rc::Bytes encode_scene(const render::SceneImage& s) {
  if (s.objects.size() > 0xFFFF || s.width > 0xFFFF || s.height > 0xFFFF || s.max_depth > 0xFF ||
      s.lights.size() > 0xFF || s.materials.size() > 0xFF)
    throw rc::ProtocolError("scene download: " + std::to_string(s.objects.size()) + " objects, " +
                            std::to_string(s.width) + "x" + std::to_string(s.height) +
                            " pixels or depth " + std::to_string(s.max_depth) + " do not fit the message");
  Writer w;
  w.words(s.eye);
  w.words(s.look_at);
  w.words(s.up);
  w.word(s.fov_deg);
  w.u16(static_cast<unsigned>(s.width));
  w.u16(static_cast<unsigned>(s.height));
  w.u8(static_cast<unsigned>(s.max_depth));
  w.words(s.background);
  w.word(s.epsilon);
  w.u8(static_cast<unsigned>(s.lights.size()));
  for (const auto& l : s.lights) w.words(l);
  w.u8(static_cast<unsigned>(s.materials.size()));
  for (const auto& m : s.materials) {
    w.words(m.w);
    w.word(m.checker_scale);
  }
  w.u16(static_cast<unsigned>(s.objects.size()));
  for (const auto& o : s.objects) {
    w.u8((o.solid ? 1u : 0u) | static_cast<unsigned>(o.combine) << 1);  // one byte: solid, CombineCode
    w.u8(static_cast<unsigned>(o.material));
    w.u32(static_cast<std::uint32_t>(o.first_prim));
    w.u32(static_cast<std::uint32_t>(o.prim_count));
    w.words(o.box_min);
    w.words(o.box_max);
  }
  w.u32(static_cast<std::uint32_t>(s.prims.size()));
  // Type byte, bit 7: a solid of revolution's slab follows the words.
  for (const auto& p : s.prims) {
    const bool slab = p.slab != decltype(p.slab){};
    w.u8(static_cast<unsigned>(p.type) | (slab ? kSlabFollows : 0u));
    w.u16(static_cast<unsigned>(p.object));
    w.words(p.w);
    if (slab) w.words(p.slab);
  }
  return w.take();
}

render::SceneImage decode_scene(const rc::Bytes& b) {
  Reader r(b, "scene");
  render::SceneImage s;
  r.words(s.eye);
  r.words(s.look_at);
  r.words(s.up);
  s.fov_deg = r.word();
  s.width = static_cast<int>(r.u16());
  s.height = static_cast<int>(r.u16());
  s.max_depth = static_cast<int>(r.u8());
  r.words(s.background);
  s.epsilon = r.word();
  s.lights.resize(r.u8());
  for (auto& l : s.lights) r.words(l);
  s.materials.resize(r.u8());
  for (auto& m : s.materials) {
    r.words(m.w);
    m.checker_scale = r.word();
  }
  const unsigned objects = r.u16();
  r.count_check(objects, 2 + 8 + 18);
  s.objects.resize(objects);
  for (auto& o : s.objects) {
    const unsigned kind = r.u8();
    o.solid = (kind & 1) != 0;
    o.combine = static_cast<int>(kind >> 1);
    if (o.combine > render::kDifference)
      throw rc::ProtocolError("scene download: an object's kind byte " + std::to_string(kind) +
                              " (bit 0 solid, bits 1.. a combination 0..2)");
    o.material = static_cast<int>(r.u8());
    o.first_prim = static_cast<int>(r.u32());
    o.prim_count = static_cast<int>(r.u32());
    r.words(o.box_min);
    r.words(o.box_max);
  }
  const std::uint32_t prims = r.u32();
  r.count_check(prims, 3 + 3 * render::image_words::kTriWords);
  s.prims.resize(prims);
  for (auto& p : s.prims) {
    const unsigned type = r.u8();
    p.type = static_cast<int>(type & ~kSlabFollows);
    p.object = static_cast<int>(r.u16());
    r.words(p.w);
    if (type & kSlabFollows) r.words(p.slab);
  }
  r.end();
  for (const auto& o : s.objects)
    if (o.first_prim < 0 || o.prim_count < 0 ||
        static_cast<std::uint64_t>(o.first_prim) + static_cast<std::uint64_t>(o.prim_count) > prims)
      throw rc::ProtocolError("scene download: an object's primitives " + std::to_string(o.first_prim) + " + " +
                              std::to_string(o.prim_count) + " exceed the " + std::to_string(prims) + " sent");
  return s;
}

rc::Bytes encode_kernel(const std::string& name, const std::vector<apu::Encoded>& words) {
  Writer w;
  w.u8(static_cast<unsigned>(name.size()));
  for (char c : name) w.u8(static_cast<unsigned char>(c));
  w.u16(static_cast<unsigned>(words.size()));
  for (const apu::Encoded& x : words) {
    w.u64(x.lo);
    w.u64(x.hi);
  }
  return w.take();
}

KernelDownload decode_kernel(const rc::Bytes& b) {
  Reader r(b, "kernel");
  KernelDownload k;
  const unsigned n = r.u8();
  for (unsigned i = 0; i < n; ++i) k.name.push_back(static_cast<char>(r.u8()));
  const unsigned words = r.u16();
  r.count_check(words, 16);
  k.words.resize(words);
  for (auto& x : k.words) {
    x.lo = r.u64();
    x.hi = r.u64();
  }
  r.end();
  return k;
}

std::vector<std::uint32_t> object_work(const render::SceneImage& scene) {
  std::vector<std::uint32_t> work;
  for (const render::ObjectImage& o : scene.objects) {
    const bool secondary = render::spawns_secondary(scene.materials.at(static_cast<std::size_t>(o.material)));
    work.push_back(static_cast<std::uint32_t>(o.prim_count) * (secondary ? 4 : 1));
  }
  return work;
}

rc::FramePlan frame_plan(const render::SceneImage& scene, unsigned block_w, unsigned block_h) {
  rc::FramePlan p;
  // s2: programs and data by broadcast: the kernels, then the scene.
  for (const render::KernelImage& k : render::kernel_images())
    p.downloads.push_back(
        rc::encode(rc::DownloadMsg{static_cast<std::uint8_t>(rc::DownloadTag::Kernel),
                                   encode_kernel(k.name, render::kernel_words(k.name))}));
  p.downloads.push_back(
      rc::encode(rc::DownloadMsg{static_cast<std::uint8_t>(rc::DownloadTag::Scene), encode_scene(scene)}));
  p.downloads.push_back(rc::encode(rc::RenderSetupMsg{
      static_cast<std::uint16_t>(scene.width), static_cast<std::uint16_t>(scene.height),
      static_cast<std::uint16_t>(block_w), static_cast<std::uint16_t>(block_h)}));
  p.blocks = rc::split_screen(static_cast<unsigned>(scene.width), static_cast<unsigned>(scene.height), block_w,
                              block_h);
  p.block_lists = true;
  p.fault_tolerant = true;
  p.object_work = object_work(scene);
  return p;
}

}  // namespace mc1::render_nc
