#pragma once
// §II.C: an edge cut by the view is never a static edge, and the view is learnt as the sensor
// reports (LearnedFrustum): a wall's far end at the range creeps along with the sensor, so the
// sightings before the range was learnt agree with it and it passed for the wall's end.

#include "grouping/group.hpp"
#include "localisation/frustum.hpp"
#include "plane_store/plane_store.hpp"
#include "plane_store/sensing.hpp"

namespace relplane::mapper {

// Marks the stored edges `frustum` now finds cut that were judged uncut before it knew its range
// limit, and those it finds coarse (Observe) that were judged before it knew its angular step,
// with the sightings kept from them (a plane's first, a group's when made and from fixed poses),
// and has the groups holding them built again. Returns how many edges it marked.
int MarkViewCuts(const LearnedFrustum& frustum, double static_std, PlaneStore& store,
                 Grouping& grouping);

}  // namespace relplane::mapper
