# Sourced on the GPU machine by the bundle's scripts (run_device.sh, memo_sweep.sh,
# memo_quality.sh --gpu): installs the carried Vulkan loader, libglvnd and meshoptimizer
# (.gl/*.deb, see tools/bundle_device.sh) and points the loader at NVIDIA's ICD where the image keeps it
# outside the standard folders. tools/bundle_device.sh copies it to bundle/device_env.sh.
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
if ! ls /usr/share/vulkan/icd.d/nvidia_icd.json /etc/vulkan/icd.d/nvidia_icd.json >/dev/null 2>&1; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
