# Installation and the Debian packages (CPack): lineloc-robot, the onboard
# agent and its camera tools, which need no database; lineloc-backbone, the
# server with the database's loader, migrations (embedded in lineloc-migrate)
# and enrichment tools. Each carries its systemd unit and its configuration
# under /etc/lineloc (conffiles: an upgrade keeps the site's edits).
# `cpack -G DEB` in the build folder writes both.

set(LINELOC_PACKAGING_DIR ${PROJECT_SOURCE_DIR}/deploy/packaging)

install(TARGETS lineloc-robot lineloc-calibrate lineloc-features RUNTIME DESTINATION bin
        COMPONENT robot)
install(FILES ${LINELOC_PACKAGING_DIR}/robot.yml DESTINATION /etc/lineloc COMPONENT robot)
install(FILES ${LINELOC_PACKAGING_DIR}/lineloc-robot.service DESTINATION /lib/systemd/system
        COMPONENT robot)

install(TARGETS lineloc-backbone lineloc-load lineloc-migrate lineloc-enrich lineloc-enrichment
        RUNTIME DESTINATION bin COMPONENT backbone)
install(FILES ${LINELOC_PACKAGING_DIR}/backbone.yml DESTINATION /etc/lineloc COMPONENT backbone)
install(FILES ${LINELOC_PACKAGING_DIR}/lineloc-backbone.service DESTINATION /lib/systemd/system
        COMPONENT backbone)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/deploy/dds-security.sh DESTINATION share/lineloc
        COMPONENT backbone)

# The loopback-only Cyclone DDS configuration both configs name.
foreach(component robot backbone)
  install(FILES ${PROJECT_SOURCE_DIR}/deploy/cyclonedds.xml DESTINATION share/lineloc
          COMPONENT ${component})
  file(WRITE ${CMAKE_BINARY_DIR}/packaging/${component}/conffiles "/etc/lineloc/${component}.yml\n")
endforeach()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lineloc)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "localisation of a robot against a 3D city model")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL robot backbone)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "lineloc developers")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_ROBOT_PACKAGE_NAME lineloc-robot)
set(CPACK_DEBIAN_ROBOT_DESCRIPTION
    "lineloc's onboard agent: the camera's lines to the backbone, its pose fixes into the robot's navigator")
set(CPACK_DEBIAN_ROBOT_PACKAGE_CONTROL_EXTRA ${CMAKE_BINARY_DIR}/packaging/robot/conffiles)
set(CPACK_DEBIAN_BACKBONE_PACKAGE_NAME lineloc-backbone)
set(CPACK_DEBIAN_BACKBONE_DESCRIPTION
    "lineloc's server: pose fixes for the robots from a PostGIS building database, and its loader")
set(CPACK_DEBIAN_BACKBONE_PACKAGE_CONTROL_EXTRA ${CMAKE_BINARY_DIR}/packaging/backbone/conffiles)
include(CPack)
