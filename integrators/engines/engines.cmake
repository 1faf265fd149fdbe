# The external engines, each optional: found ones are compiled into contact_integrators (their
# methods join the registry), missing ones are named at configure time and in
# engines_missing(). scripts/setup.sh installs all of them.
find_package(PkgConfig QUIET)
find_package(mujoco CONFIG QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(BULLET QUIET IMPORTED_TARGET bullet-float64)
  pkg_check_modules(ODE QUIET IMPORTED_TARGET ode)
endif()

set(missing "")
# engine(NAME TARGET SOURCE PACKAGES): compile SOURCE in, linked to TARGET, when TARGET exists.
function(engine name target source packages)
  string(TOUPPER ${name} upper)
  if(TARGET ${target})
    target_sources(contact_integrators PRIVATE engines/${source})
    target_link_libraries(contact_integrators PRIVATE ${target})
    target_compile_definitions(contact_integrators PRIVATE CONTACT_ODE_WITH_${upper})
    set(CONTACT_ODE_ENGINES ${CONTACT_ODE_ENGINES} ${name} PARENT_SCOPE)
  else()
    set(missing ${missing} "${name} (${packages})" PARENT_SCOPE)
  endif()
endfunction()
engine(mujoco mujoco::mujoco mujoco_engine.cpp "libmujoco-dev libqhull-dev")
engine(bullet PkgConfig::BULLET bullet_engine.cpp "libbullet-dev")
engine(ode PkgConfig::ODE ode_engine.cpp "libode-dev")

# Siconos: Boost before its config, which sets CMAKE_CXX_STANDARD 11 in the caller's scope (kept
# inside this function's); its headers need C++17, so they compile alone in an object library.
function(find_siconos)
  find_package(Boost QUIET)
  if(Boost_FOUND)
    find_package(siconos CONFIG QUIET)
  endif()
endfunction()
find_siconos()
if(TARGET Siconos::kernel)
  add_library(contact_siconos OBJECT engines/siconos_line.cpp)
  set_target_properties(contact_siconos PROPERTIES CXX_STANDARD 17 POSITION_INDEPENDENT_CODE ON)
  target_link_libraries(contact_siconos PRIVATE Siconos::kernel Siconos::numerics)
endif()
engine(siconos Siconos::kernel siconos_engine.cpp "libsiconos-kernel-dev libsiconos-mechanics-dev python3-siconos")
if(TARGET Siconos::kernel)
  target_sources(contact_integrators PRIVATE $<TARGET_OBJECTS:contact_siconos>)
  target_link_libraries(contact_integrators PRIVATE Siconos::numerics)
endif()

list(JOIN missing ", " missing_text)
set_source_files_properties(engines/engine_world.cpp PROPERTIES
  COMPILE_DEFINITIONS "CONTACT_ODE_ENGINES_MISSING=\"${missing_text}\"")
if(missing)
  message(STATUS "contact-ode: built without the engines ${missing_text}; scripts/setup.sh installs them")
endif()
set(CONTACT_ODE_ENGINES "${CONTACT_ODE_ENGINES}" PARENT_SCOPE)
