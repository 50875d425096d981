# dyngi_add_shaders(TARGET <lib> NAMESPACE <c++ namespace> INCLUDE_DIRS <dirs...> SOURCES <glsl files...>)
#
# Compiles each GLSL file to SPIR-V with glslangValidator at build time (a shader error fails the
# build) and embeds the words in a generated header <name>.spv.h as `uint32_t <stem>_<stage>[]`.
# The headers land in ${CMAKE_CURRENT_BINARY_DIR}/spirv, which is added to TARGET's include path,
# so C++ includes them as "spirv/gbuffer.vert.spv.h".
function(dyngi_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "INCLUDE_DIRS;SOURCES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  set(include_flags)
  set(all_headers)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I${dir})
    file(GLOB_RECURSE dir_headers ${dir}/*.h ${dir}/*.glsl)
    list(APPEND all_headers ${dir_headers})
  endforeach()
  set(outputs)
  foreach(src ${ARG_SOURCES})
    get_filename_component(name ${src} NAME)
    string(REPLACE "." "_" var ${name})
    set(out ${out_dir}/${name}.spv.h)
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.2 -g0 ${include_flags}
              --vn spv_${var} -o ${out} ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${src} ${all_headers}
      COMMENT "GLSL -> SPIR-V ${name}"
      VERBATIM)
    list(APPEND outputs ${out})
  endforeach()
  add_custom_target(${ARG_TARGET}_shaders DEPENDS ${outputs})
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_shaders)
  target_include_directories(${ARG_TARGET} PRIVATE ${CMAKE_CURRENT_BINARY_DIR})
endfunction()
