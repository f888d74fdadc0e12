#pragma once
// The viewer's pieces beside its main loop: the fly/orbit camera, the per-frame command
// buffer and synchronisation objects, and screenshots.
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include <facet/gpu/context.h>
#include <facet/io/image_io.h>
#include <facet/render/camera.h>
#include "check_vk.h"

namespace facet {

// Fly camera (yaw/pitch around the position) or orbit camera (around the target).
struct CameraControl {
    CameraView view, home;
    bool orbit = false;
    double last_x = 0, last_y = 0;
    bool dragging = false;

    void update(GLFWwindow* window, double seconds) {
        glm::vec3 forward = glm::normalize(view.target - view.position);
        const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
        const float speed = 0.5f * glm::length(home.target - home.position) * float(seconds);
        glm::vec3 move(0.0f);
        if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) move += forward;
        if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) move -= forward;
        if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) move += right;
        if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) move -= right;
        view.position += move * speed;
        if (!orbit) view.target += move * speed;
        double x, y;
        glfwGetCursorPos(window, &x, &y);
        const bool pressed = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        if (pressed && dragging) {
            const float yaw = float(x - last_x) * -0.005f, pitch = float(y - last_y) * -0.005f;
            const glm::vec3 pivot = orbit ? view.target : view.position;
            glm::vec3 arm = orbit ? view.position - view.target : view.target - view.position;
            const glm::mat4 turn = glm::rotate(glm::rotate(glm::mat4(1.0f), yaw, glm::vec3(0, 1, 0)), pitch, right);
            arm = glm::vec3(turn * glm::vec4(arm, 0.0f));
            if (std::abs(glm::normalize(arm).y) < 0.99f) {
                if (orbit) view.position = pivot + arm;
                else view.target = pivot + arm;
            }
        }
        dragging = pressed;
        last_x = x;
        last_y = y;
    }
};

inline CameraControl* control_of(GLFWwindow* w) { return static_cast<CameraControl*>(glfwGetWindowUserPointer(w)); }

// One frame in flight: its command buffer, the swapchain semaphores and a fence.
struct FrameSync {
    VkDevice device;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE, rendered = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;
    explicit FrameSync(Context& c) : device(c.device()) {
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = c.queue_family();
        check_vk(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        check_vk(vkAllocateCommandBuffers(device, &alloc, &cmd), "vkAllocateCommandBuffers");
        VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        check_vk(vkCreateSemaphore(device, &semaphore, nullptr, &acquired), "vkCreateSemaphore");
        check_vk(vkCreateSemaphore(device, &semaphore, nullptr, &rendered), "vkCreateSemaphore");
        VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check_vk(vkCreateFence(device, &fence, nullptr, &done), "vkCreateFence");
    }
    ~FrameSync() {
        vkDestroyFence(device, done, nullptr);
        vkDestroySemaphore(device, rendered, nullptr);
        vkDestroySemaphore(device, acquired, nullptr);
        vkDestroyCommandPool(device, pool, nullptr);
    }
};

// A screenshot: .exr linear (the exposure applied), anything else the display image.
inline Status save(const std::string& path, uint32_t w, uint32_t h, const std::vector<std::byte>& ldr,
            const std::vector<float>& hdr, float exposure) {
    if (path.size() > 4 && path.substr(path.size() - 4) == ".exr") {
        std::vector<float> exposed = hdr;
        for (size_t i = 0; i < exposed.size(); ++i)
            if (i % 4 != 3) exposed[i] *= exposure;
        return write_hdr_image(path, w, h, exposed);
    }
    std::vector<uint8_t> bytes(ldr.size());
    std::memcpy(bytes.data(), ldr.data(), ldr.size());
    return write_ldr_image(path, w, h, bytes);
}

}  // namespace facet
