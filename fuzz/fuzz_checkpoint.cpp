// libFuzzer target: what `sinew run --resume` reads from an output folder, in its order:
// checkpoint.json (read_checkpoint), the frame records of frames.jsonl (read_frame_log) and the
// integrator's own state (restore_integrator), for the energy-limited scene
// tests/data/checkpoint_scene. An input is the checkpoint, optionally followed by a line
// "---frames.jsonl---" and the frame records. The seeds (fuzz/seeds/fuzz_checkpoint) are that
// scene's, carrying its fingerprints, so mutations get past the fingerprint checks to the state,
// the frame records and the multipliers.
#include "support.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/frame_log.hpp"

namespace {

struct Resumable {
  Resumable()
      : scene(sinew::load_scene(SINEW_CHECKPOINT_SCENE)),
        model(sinew::build_model(scene)),
        fingerprint(sinew::fingerprint_run(scene)) {}
  sinew::Scene scene;
  sinew::Model model;
  sinew::RunFingerprint fingerprint;
};

Resumable& resumable() {
  static Resumable r;
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Resumable& r = resumable();
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string separator = "\n---frames.jsonl---\n";
  const std::size_t split = input.find(separator);
  const auto checkpoint = sinew::fuzz::write_input(input.substr(0, split), "checkpoint.json");
  const auto frames = sinew::fuzz::write_input(
      split == std::string::npos ? std::string() : input.substr(split + separator.size()), "frames.jsonl");
  const auto out = checkpoint.parent_path();
  sinew::fuzz::expect_clean(
      [&] {
        const sinew::Checkpoint c =
            sinew::read_checkpoint(out, r.fingerprint, *r.model.integrator, r.model.initial.x.size(), r.scene.frames);
        sinew::read_frame_log(out, c.frame);
        sinew::restore_integrator(*r.model.integrator, c, out);
      },
      {checkpoint, frames});
  return 0;
}
