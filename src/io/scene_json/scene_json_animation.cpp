// Spec §22 in scene files: the "animation" clock and keyed "transform" and
// "camera" values.
#include <cmath>
#include <initializer_list>
#include <string>

#include "io/scene_json/scene_json.h"

namespace sombra {

namespace {

// Frames are counted in 32 bits' worth either way: far beyond any film,
// and frame / fps stays exact in double.
constexpr std::int64_t kMaxFrame = std::int64_t{1} << 31;

// The "time" of a key, finite and later than the previous key's.
double read_key_time(const SceneJson& s, const Json& key, const std::string& pointer, std::size_t index,
                     double previous) {
    const std::string p = json_child(pointer, "time");
    const double time = read_float(s, require_member(s, key, pointer, "time"), p);
    if (index > 0 && !(time > previous))
        json_fail(s, p, "key times must increase: " + std::to_string(time) + " follows " + std::to_string(previous));
    return time;
}

// The "keys" array of a keyed value: at least one entry. A keyed camera
// may also name its medium (spec §26), which no key changes.
const Json& read_keys(const SceneJson& s, const Json& v, std::string_view pointer, bool camera = false) {
    expect_object(s, v, pointer);
    if (camera)
        expect_keys(s, v, pointer, {"keys", "medium"});
    else
        expect_keys(s, v, pointer, {"keys"});
    const std::string p = json_child(pointer, "keys");
    const Json& keys = require_member(s, v, pointer, "keys");
    expect_array(s, keys, p);
    if (keys.empty()) json_fail(s, p, "expected at least one key");
    return keys;
}

// The keys of a keyed value, each an object with an increasing "time" and,
// unless `members` is empty, no other member than those;
// read_key(key, its pointer, its time) reads the rest of one.
template <class Key, class ReadKey>
std::vector<Key> read_keyed(const SceneJson& s, const Json& v, std::string_view pointer,
                            std::initializer_list<std::string_view> members, ReadKey read_key, bool camera = false) {
    const Json& keys = read_keys(s, v, pointer, camera);
    const std::string keys_pointer = json_child(pointer, "keys");
    std::vector<Key> out;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const std::string p = json_child(keys_pointer, i);
        expect_object(s, keys[i], p);
        if (members.size() > 0) expect_keys(s, keys[i], p, members);
        const double time = read_key_time(s, keys[i], p, i, out.empty() ? 0.0 : out.back().time);
        out.push_back(read_key(keys[i], p, time));
    }
    return out;
}

}  // namespace

SceneClock read_animation(const SceneJson& s, const Json& v, std::string_view pointer) {
    expect_object(s, v, pointer);
    expect_keys(s, v, pointer, {"fps", "frames"});
    SceneClock clock;
    if (const Json* fps = find_member(v, "fps")) {
        const std::string p = json_child(pointer, "fps");
        clock.fps = read_float(s, *fps, p);
        if (!(clock.fps > 0) || clock.fps > 1e6) json_fail(s, p, "fps must be greater than 0 (and at most 1e6)");
    }
    if (const Json* frames = find_member(v, "frames")) {
        const std::string p = json_child(pointer, "frames");
        if (!frames->is_array() || frames->size() != 2) json_fail(s, p, "expected [first, last], two integers");
        clock.first_frame = read_integer(s, (*frames)[0], json_child(p, 0), -kMaxFrame, kMaxFrame);
        clock.last_frame = read_integer(s, (*frames)[1], json_child(p, 1), -kMaxFrame, kMaxFrame);
        if (clock.last_frame < clock.first_frame) json_fail(s, p, "the last frame comes before the first");
    }
    return clock;
}

std::vector<TransformKey> read_transform_keys(const SceneJson& s, const Json& v, std::string_view pointer) {
    return read_keyed<TransformKey>(
        s, v, pointer, {"time", "transform"}, [&](const Json& key, const std::string& p, double time) {
            return TransformKey{time,
                                read_transform(s, require_member(s, key, p, "transform"), json_child(p, "transform"))};
        });
}

std::vector<CameraKey> read_camera_keys(const SceneJson& s, const Json& v, std::string_view pointer) {
    // The camera's own reader checks its members (read_camera).
    return read_keyed<CameraKey>(
        s, v, pointer, {},
        [&](const Json& key, const std::string& p, double time) {
            // The rest of the key is a camera object of the look-at form (spec §22).
            Json camera = key;
            camera.erase("time");
            if (camera.contains("medium"))
                json_fail(s, json_child(p, "medium"), "the camera's medium goes beside 'keys': no key changes it");
            const CameraSpec spec = read_camera(s, camera, p);
            if (!spec.look_at) json_fail(s, p, "a camera key is a look-at camera: 'origin', 'look_at', 'up', 'fov'");
            return CameraKey{time,
                             spec.look_at->origin,
                             spec.look_at->look_at,
                             spec.look_at->up,
                             spec.look_at->fov_degrees,
                             spec.aperture_radius,
                             spec.focus_distance};
        },
        true);
}

}  // namespace sombra
