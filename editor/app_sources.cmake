# The interactive editor's sources (editor/app.*, navigation, session, tools), included by editor/CMakeLists.txt.
# They need trispline_ui (ImGui panels), trispline_gpu (window, renderer) and core; the editor target links them.
set(TRISPLINE_EDITOR_APP_SOURCES
    app.cpp
    app_bench.cpp
    app_requests.cpp
    session/background_command.cpp
    gui_probe.cpp
    guarantees_view.cpp
    animation_ui.cpp
    session/navigation.cpp
    session/session.cpp
    volume_ui.cpp
    tools/select_tool.cpp
    tools/toolbox.cpp
    tools/work_queue.cpp
    tools/sketch_tool.cpp
    tools/press_tool.cpp
    tools/incision_tool.cpp
    tools/tool.cpp
    tools/keyed_weight_section.cpp
    tools/dffd_tool.cpp
    tools/ddm_paint_tool.cpp
    tools/ddm_paint_export.cpp
    tools/transform_modal.cpp)
