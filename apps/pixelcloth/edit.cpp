// pixelcloth edit: edit a cloth image (shift, inflate, brush, masked blend; paper appendix B), EXR + PNG preview.
#include "pixelcloth/patches/edit.h"

#include <memory>

#include "pixelcloth/core/error.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/viz/pictures.h"
#include "verbs.h"

namespace pixelcloth::apps {

namespace {
struct EditArgs {
  std::string image;
  std::string out;
  std::vector<float> shift;
  float inflate = 1.0f;
  float inflateAdd = 0.0f;
  std::vector<double> brush;
  std::string blend;
  std::string mask;
  std::string region;
};

void runEdit(const EditArgs& args, bool inflateGiven, bool inflateAddGiven) {
  using namespace pixelcloth::core;
  using namespace pixelcloth::body;
  using namespace pixelcloth::garment;
  using namespace pixelcloth::viz;
  using namespace pixelcloth::patches;
  const int edits = !args.shift.empty() + (inflateGiven || inflateAddGiven) + !args.brush.empty() + !args.blend.empty();
  PIXELCLOTH_CHECK(
      edits == 1, "edit: give exactly one of --shift, --inflate/--inflate-add, --brush, --blend (got " << edits << ")");
  PIXELCLOTH_CHECK(args.blend.empty() == args.mask.empty(), "edit: --blend and --mask go together");
  std::filesystem::path out(args.out);
  PIXELCLOTH_CHECK(out.extension() == ".exr", args.out << ": the output must be an .exr file");
  ClothImage image = readClothImage(args.image);
  Eigen::MatrixXf region;
  if (!args.region.empty()) region = readEditMask(args.region, image);
  if (!args.shift.empty()) shiftImage(image, args.shift[0], args.shift[1], region);
  if (inflateGiven || inflateAddGiven) inflateImage(image, args.inflate, args.inflateAdd, region);
  if (!args.brush.empty())
    brushImage(image, {args.brush[0], args.brush[1], args.brush[2], static_cast<float>(args.brush[3])});
  if (!args.blend.empty()) {
    ClothImage other = readClothImage(args.blend);
    Eigen::MatrixXf alpha = readEditMask(args.mask, image);
    if (region.size() > 0) PIXELCLOTH_FAIL("edit: --region does not apply to --blend (use --mask)");
    blendImages(image, other, alpha);
  }
  image.source.clear();
  writeClothImage(out, image);
  std::filesystem::path preview = out;
  preview.replace_extension(".png");
  writePng(preview, renderClothImage(image));
  PIXELCLOTH_INFO("edit: " << args.image << " -> " << out.string() << ", " << preview.string());
}
}  // namespace

void registerEdit(CLI::App& app) {
  auto args = std::make_shared<EditArgs>();
  CLI::App* verb = app.add_subcommand(
      "edit",
      "Edit a cloth image (paper appendix B): shift du/dv, inflate or shrink dn, paint dn with a brush, or "
      "blend in a second image through a mask; writes the EXR and a PNG preview next to it");
  verb->add_option("--image", args->image, "Cloth image to edit (EXR)")->required();
  verb->add_option("--out", args->out, "Edited cloth image (EXR); the preview goes to the same name with .png")
      ->required();
  verb->add_option("--shift", args->shift, "DU DV: add these offsets (metres) to du and dv (default: no shift)")
      ->expected(2);
  CLI::Option* inflate =
      verb->add_option("--inflate", args->inflate, "S: scale dn by S (inflate > 1, shrink < 1; default 1)");
  CLI::Option* inflateAdd = verb->add_option("--inflate-add", args->inflateAdd,
                                             "A: add A metres to dn (with or without --inflate; default 0)");
  verb->add_option("--brush", args->brush,
                   "X Y R DN: add DN metres to dn at preview pixel (X, Y) with a smooth falloff to 0 at radius R "
                   "pixels (layers side by side as in the preview; default: no brush)")
      ->expected(4);
  verb->add_option("--blend", args->blend, "Second cloth image (EXR) to blend in through --mask (default: none)");
  verb->add_option("--mask", args->mask,
                   "Blend alpha as a PNG (grey/255; width x height, or layers side by side; default: none)");
  verb->add_option("--region", args->region,
                   "Limit --shift / --inflate to this alpha PNG (same sizes as --mask; default: the whole image)");
  verb->callback([args, inflate, inflateAdd] { runEdit(*args, inflate->count() > 0, inflateAdd->count() > 0); });
}

}  // namespace pixelcloth::apps
