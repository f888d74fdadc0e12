#include "render/lobe_disks.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/glm.hpp>

namespace facet {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Group {
    std::vector<size_t> members;
    DiskLight merged;
};

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// The solid angle of a cap of angular radius theta, 2 pi (1 - cos theta), as the shaders
// take it (render/light_data.h, disk_data): a disk's power there is its radiance times this.
double cap_solid_angle(double theta) {
    const double half_chord = std::sin(0.5 * theta);
    return 4.0 * kPi * half_chord * half_chord;
}

glm::dvec3 cap_power(const DiskLight& d) { return glm::dvec3(d.radiance) * cap_solid_angle(d.angular_radius); }

double angle(const glm::dvec3& a, const glm::dvec3& b) {
    // atan2 of the cross and dot products: exact for small angles, where acos is not.
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The one cap that stands for `members` of `disks`: their power, mean direction and spread.
DiskLight merge(std::span<const DiskLight> disks, const std::vector<size_t>& members, double* radius) {
    if (members.size() == 1) {
        *radius = disks[members[0]].angular_radius;
        return disks[members[0]];
    }
    glm::dvec3 power(0.0), axis(0.0);
    double weight = 0.0, power_fraction = 0.0;
    uint32_t texels = 0;
    for (size_t i : members) {
        const DiskLight& d = disks[i];
        const glm::dvec3 p = cap_power(d);
        const double w = std::max(luminance(p), 1e-30);
        power += p;
        weight += w;
        axis += w * glm::dvec3(d.direction);
        power_fraction += d.power_fraction;
        texels += d.texels;
    }
    const glm::dvec3 centre = glm::length(axis) > 0.0 ? glm::normalize(axis) : glm::dvec3(disks[members[0]].direction);
    double spread = 0.0;  // mean squared angle from the centre
    double reach = 0.0;   // the farthest edge of a member from the centre
    for (size_t i : members) {
        const DiskLight& d = disks[i];
        const double w = std::max(luminance(cap_power(d)), 1e-30);
        const double offset = angle(centre, glm::dvec3(d.direction));
        spread += w * (offset * offset + 0.5 * double(d.angular_radius) * d.angular_radius);
        reach = std::max(reach, offset + double(d.angular_radius));
    }
    spread /= weight;
    const double theta = std::min(std::sqrt(2.0 * spread), kPi / 2);
    const double solid_angle = cap_solid_angle(theta);
    DiskLight m;
    m.direction = glm::vec3(centre);
    m.angular_radius = float(theta);
    m.solid_angle = float(solid_angle);
    m.radiance = glm::vec3(power / solid_angle);
    m.texels = texels;
    m.power_fraction = power_fraction;
    // A faint cap far away barely moves the spread, but its light would move: the group is
    // as wide as its farthest member's edge.
    *radius = std::max(theta, reach);
    return m;
}

}  // namespace

bool disk_is_point_for_lobe(const DiskLight& disk, float roughness) {
    return double(roughness) * roughness >= double(kPointCapLobeRatio) * disk.angular_radius;
}

std::vector<DiskLight> disks_for_lobe(std::span<const DiskLight> disks, float roughness) {
    const double alpha = double(roughness) * roughness;
    const double limit = std::min(double(kMergedCapLobeFraction) * alpha, double(kMergedCapMaxRadius));
    std::vector<size_t> order(disks.size());
    std::iota(order.begin(), order.end(), size_t(0));
    auto power = [&](size_t i) { return luminance(cap_power(disks[i])); };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return power(a) > power(b); });
    std::vector<Group> groups;
    for (size_t i : order) {
        bool joined = false;
        for (Group& g : groups) {
            std::vector<size_t> members = g.members;
            members.push_back(i);
            double radius = 0.0;
            DiskLight merged = merge(disks, members, &radius);
            if (radius <= limit) {
                g.members = std::move(members);
                g.merged = merged;
                joined = true;
                break;
            }
        }
        if (!joined) {
            Group g;
            g.members = {i};
            g.merged = disks[i];
            groups.push_back(std::move(g));
        }
    }
    // In the order of each group's first cap in `disks`: where nothing merges, `disks` as given.
    std::stable_sort(groups.begin(), groups.end(), [](const Group& a, const Group& b) {
        return *std::min_element(a.members.begin(), a.members.end()) <
               *std::min_element(b.members.begin(), b.members.end());
    });
    std::vector<DiskLight> out;
    out.reserve(groups.size());
    for (const Group& g : groups) out.push_back(g.merged);
    return out;
}

}  // namespace facet
