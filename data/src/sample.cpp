#include "pixelcloth/data/sample.h"

#include "pixelcloth/core/enum_names.h"

namespace pixelcloth::data {

namespace {
const core::EnumNames<Rejection, 7> kRejections{"rejection",
                                                {{{Rejection::None, "none"},
                                                  {Rejection::TriangleShrank, "triangle_shrank"},
                                                  {Rejection::TriangleGrew, "triangle_grew"},
                                                  {Rejection::NotFinite, "not_finite"},
                                                  {Rejection::ArmInsideTorso, "arm_inside_torso"},
                                                  {Rejection::Penetrated, "penetrated"},
                                                  {Rejection::NotConverged, "not_converged"}}}};
}  // namespace

const char* rejectionName(Rejection rejection) { return kRejections.name(rejection); }

}  // namespace pixelcloth::data
