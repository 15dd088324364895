"""Shared test helpers: loading the example models from models/."""
import importlib.util
import os
import sys

import numpy as np
import pytest

# The suite compiles native code before a run (as before issue 30's tiers), so that a test
# sees the same path on a cold and a warm cache; tests/test_native_tiers.py sets "auto".
os.environ.setdefault("ACAUSAL2D_NATIVE", "now")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")


def load_model_class(filename, classname):
    """Import ``models/<filename>`` and return the class ``classname``."""
    if MODELS not in sys.path:
        sys.path.insert(0, MODELS)
    path = os.path.join(MODELS, filename)
    name = "models_" + os.path.splitext(filename)[0]
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
    return getattr(sys.modules[name], classname)


@pytest.fixture
def model_class():
    return load_model_class


_COMPILED = {}


@pytest.fixture(scope="session")
def compiled_model():
    """``compiled_model(filename, classname)``: the compiled model of
    ``models/<filename>``'s class with its default parameters, compiled
    once per test run (per worker under xdist) and shared by the tests that
    only simulate it (a compiled model keeps no state between runs; a test
    that inspects or changes what compiling builds compiles its own)."""
    import acausal2d

    def get(filename, classname):
        key = (filename, classname)
        if key not in _COMPILED:
            _COMPILED[key] = acausal2d.compile_model(load_model_class(filename, classname)())
        return _COMPILED[key]
    return get


# Rounding of a time placed by a few floating-point operations: an output
# point of numpy's linspace or t0 + k h, a time event's own instant (a few
# ulps of the time); 8 eps relative leaves room.
TIME_ROUNDING = 8 * np.finfo(float).eps


def same_time(times, t):
    """Where ``times`` equal ``t`` up to TIME_ROUNDING (relative to max(|t|,
    1)): output points and time events are exact in intent but placed by
    floating-point arithmetic, so they are not compared with ``==``."""
    return np.abs(np.asarray(times, dtype=float) - t) <= TIME_ROUNDING * max(abs(t), 1.0)


def assert_copied(actual, expected):
    """``actual`` holds the numbers of ``expected`` passed through code that
    does no arithmetic on them (a drawing scene, the disk cache, a CSV or
    JSON round trip written with 17 significant digits, a parameter read
    back, the same deterministic call repeated), or the constant a branch of
    the equations selects (a slack span's force, a closed valve's flow, a
    sign flag): exact equality is the claim and holds on any machine.  The only exact array comparison of the suite
    (tests/test_float_equality.py allows it here)."""
    np.testing.assert_array_equal(actual, expected)


# ---------------------------------------------------------------- the fast tier
# ``python -m pytest -m "not slow" -n auto`` is the development run (docs/guide/testing.md);
# the README's command runs everything.  Tests marked slow: subprocess-heavy command-line
# and installation tests, browser (headless Chromium) tests, the native engine's tier and
# build tests, the gallery-like runs of every model, and the fuzz cases beyond each class's
# first.  A test module marks its own tests with ``@pytest.mark.slow``; the modules below
# are slow as a whole (each test starts processes, a browser or a compiler, or runs every
# model) and are marked here, in one place.
SLOW_MODULES = {
    "test_animation.py": "headless Chromium",
    "test_animation_elements.py": "headless Chromium",
    "test_animation_sync.py": "headless Chromium",
    "test_node_drag.py": "headless Chromium",
    "test_mode_page.py": "headless Chromium",
    "test_plain_clone.py": "a clone installed into a new virtual environment",
    "test_help_examples.py": "every command's help example as a process",
    "test_bench_floor.py": "benchmark scripts as processes",
    "test_bench_small_modes.py": "benchmark scripts as processes",
    "test_native_tiers.py": "the native engine's tiers (compiler, background worker)",
    "test_native_tiers_build.py": "the native engine's build tiers (compiler)",
    "test_fmu.py": "FMUs built with the C compiler and run by fmpy",
    "test_site_build.py": "the documentation site built in a plain clone (the gallery, notebooks)",
}


SLOW_TESTS = {
    "test_ci_run.py": ["test_seen_2_ci_runs_in_a_fresh_environment"],
    "test_lint.py": ["test_mypy_passes_on_the_package"],
    "test_readme_commands.py": ["test_every_readme_command_runs_in_a_plain_clone"],
    "test_clone_root_import.py": ["test_library_imports_from_the_clone_root_without_the_installed_package"],
    "test_docs.py": ["test_tutorial_notebook_executes_and_shows_figures",
                     "test_readme_example_runs_as_printed"],
    "test_cli.py": ["test_simulated_animation_draws_in_browser",
                    "test_simulate_writes_csv_plots_and_animation",
                    "test_bad_numbers_are_errors_with_exit_code_2",
                    "test_out_on_an_existing_file_is_an_error_before_simulating",
                    "test_trace_of_a_frame_and_of_a_signal_pair",
                    "test_unknown_trace_is_an_error_before_simulating",
                    "test_simulate_with_parameter_and_stop_time",
                    "test_check_explains_a_driven_mechanism_s_dof",
                    "test_check_prints_structure_and_both_dof_counts",
                    "test_compare_passes_against_shared_reference",
                    "test_compare_fails_on_perturbed_signal",
                    "test_broken_model_gives_error_and_exit_code_2"],
    "test_compare_tube.py": ["test_double_pendulum_default_grid_passes_to_6_5_s",
                             "test_perturbed_result_fails", "test_time_tolerance_from_the_cli"],
    "test_contour_export.py": ["test_svg_draws_in_headless_chromium",
                               "test_outline_follows_the_contour"],
    "test_discoverability.py": ["test_version", "test_params_lists_value_unit_rule_and_doc",
                                "test_simulate_summary_names_the_states"],
    "test_explore.py": ["test_page_slider_changes_curve_and_animation_pin_and_error",
                        "test_bench_explore_small_prints_its_table",
                        "test_params_list_units_rules_and_ranges"],
    "test_figure_process.py": ["test_simulate_command_draws_without_importing_matplotlib",
                               "test_a_child_closed_at_once_never_runs_the_callers_code",
                               "test_child_writes_the_files_the_process_itself_writes"],
    "test_fit_cli.py": ["test_benchmark_small_mode_prints_its_table",
                        "test_fit_writes_its_files_and_the_known_values_lie_in_the_intervals"],
    "test_fuzz_output.py": ["test_sigint_and_a_second_run_never_leave_partial_or_stale_files"],
    "test_import_path.py": ["test_run_and_animation_page_import_neither_scipy_optimize_nor_matplotlib",
                            "test_scipy_optimize_after_sksundae_is_the_real_module",
                            "test_native_run_imports_no_scipy_no_scikit_sundae_no_matplotlib",
                            "test_python_path_still_imports_scikit_sundae",
                            "test_a_used_up_step_budget_stays_on_the_native_path"],
    "test_kill_during_write.py": ["test_a_killed_run_leaves_no_result_that_looks_complete"],
    "test_local_imports.py": ["test_every_function_local_import_has_a_reason",
                              "test_the_allow_lists_name_no_site_that_is_gone"],
    "test_mec2.py": ["test_cli_runs_a_json_model"],
    "test_native_cache.py": ["test_a_damaged_library_is_found_and_rebuilt",
                             "test_a_damaged_index_only_costs_a_lookup",
                             "test_an_unwritable_cache_falls_back_with_a_notice"],
    "test_native_prebuilt.py": ["test_setup_py_compiles_the_objects_into_the_package",
                                "test_an_install_without_a_compiler_goes_on_without_them",
                                "test_a_new_structure_links_the_installed_objects_and_compiles_only_its_code",
                                "test_install_compiles_every_object_with_its_digest",
                                "test_prebuilt_0_ignores_the_installed_objects"],
    "test_output_transaction.py": ["test_seen4_sigterm_after_the_csv_exits_143_and_leaves_nothing",
                                   "test_seen4_lock_of_a_killed_run_does_not_block",
                                   "test_seen4_kill_during_the_final_moves_is_cleaned_by_the_next_run",
                                   "test_seen6_figure_process_interrupted_early_ends_silently",
                                   "test_seen6_early_failure_prints_only_its_error",
                                   "test_seen4_foreign_files_in_out_are_kept",
                                   "test_seen4_plot_of_many_joined_signals_gets_a_bounded_name"],
    "test_plots.py": ["test_cli_plots_carry_units_and_model_name",
                      "test_x_axis_signal_unwrapped_in_degrees",
                      "test_belt_drive_figures_over_the_drive_angle",
                      "test_pulley_block_mu_study_from_the_cli"],
    "test_poles_transfer.py": ["test_cli_transfer_figure_and_pole_layer",
                               "test_cli_transfer_needs_x_and_valid_orders",
                               "test_browser_pole_layer_is_drawn_and_hidden_by_its_check_box"],
    "test_result_formats.py": ["test_compare_of_a_mat_reference_passes_where_its_csv_passes",
                               "test_mat_errors_name_the_file",
                               "test_piston_engine_mat_read_by_dymat_equals_the_csv",
                               "test_compare_plots_carry_units"],
    "test_sweep.py": ["test_forty_points_on_two_workers_equal_serial_runs",
                      "test_cli_sweep_on_an_existing_scheduler", "test_cli_sweep_bad_options_exit_2",
                      "test_tied_parameters_share_one_column_and_value"],
    "test_talk_synthesis.py": ["test_models_run_from_the_cli_with_figures"],
    "test_threads.py": ["test_import_and_a_run_leave_omp_num_threads_as_the_user_set_it",
                        "test_bench_threads_small_prints_its_table"],
    # sweeps whose every case builds its own native library; the fast tier keeps the
    # file's other tests of the same functions
    "test_band_synthesis.py": ["test_constant_ratio_gives_circular_cam",
                               "test_dbsd_lever_arm_equals_h"],
    # long single runs (above 4 s of CPU time each)
    "test_compressor_rounding.py": ["test_events_agree_but_for_valve_touches"],
    "test_band_balancing.py": ["test_seen_1_bounded_fit_does_not_depend_on_the_optimiser_flag"],
    "test_compile_memory.py": ["test_fifty_compiles_keep_symbol_table_and_memory_flat"],
    "test_compressor.py": ["test_periodic_steady_state"],
    "test_belt_curved.py": ["test_noncircular_drive_follows_designed_ratio",
                            "test_curved_pulley_bearing_friction_torque_balance",
                            "test_elliptic_contour_contacts_and_tangency",
                            "test_curved_drum_wound_length_is_contour_arc_length",
                            "test_support_contour_arc_length_and_polar_form"],
    "test_dummy_large.py": ["test_chain_sparse_choice_equals_dense_choice"],
    "test_fit_edges.py": ["test_seen6_cli_exit_codes_of_a_bound_and_of_the_tube"],
    "test_belt_drawing.py": ["test_cable_crane_drawing"],
    "test_modes.py": ["test_cable_crane_hook_returns_to_its_rest_position_and_swings_at_sqrt_g_over_l",
                      "test_four_bar_frequency_at_a_crank_angle_follows_its_reduced_inertia"],
    "test_output_rows.py": ["test_chain_rows_satisfy_every_equation_at_20000_points"],
    "test_planar_references.py": ["test_cli_reproduces_reference"],
    "test_modes_cli.py": ["test_modes_campbell_of_the_four_bar_follows_its_reduced_inertia"],
    # the fast tier's longest on two cores (4 s of CPU or more each, most of them a
    # command-line process, a compile into an empty cache or a browser)
    "test_seen_untrusted.py": ["test_seen_native_fallbacks_are_said_in_one_line",
                               "test_seen_planted_library_in_a_precreated_fallback_is_refused_and_never_loaded",
                               "test_seen_slow_headers_are_cut_off",
                               "test_seen_a_client_leaving_mid_body_is_one_line"],
    "test_optimize.py": ["test_four_bar_passes_its_precision_points"],
    "test_event_words.py": ["test_verbose_prints_the_relations_and_the_default_does_not"],
    "test_explore_diagram.py": ["test_diagram_opens_the_clutch_and_shows_its_parameters_and_flows"],
    "test_talk_mechanisms.py": ["test_position_correction_agrees_with_the_dae_within_its_lentol",
                                "test_node_model_agrees_with_the_vdi_elements_over_a_crank_turn",
                                "test_press_correction_needs_the_talks_iterations"],
    "test_connector_report.py": ["test_seen2_simulate_warns_about_the_loose_flanges"],
    "test_runtime_steps.py": ["test_swinging_parallelogram_steps_grow_slowly_with_the_tolerance"],
    "test_seen_bad_inputs.py": ["test_seen_other_plot_signals_leave_no_old_pngs",
                                "test_seen_failing_run_leaves_no_previous_results",
                                "test_seen_stop_time_inf_is_refused_and_keeps_nothing_stale"],
    "test_diagram.py": ["test_simulate_writes_the_diagram_with_its_outputs",
                        "test_check_of_a_broken_model_still_writes_the_diagram", "test_cli_diagram_and_check_write_it"],
    "test_when_model_does_not_run_doc.py": [
        "test_the_set_suggestion_and_the_event_words_are_on_the_page"],
    "test_native_capi.py": ["test_bench_capi_small_prints_its_table"],
    "test_native_lu.py": ["test_the_lu_is_found_in_a_process_that_loaded_scikit_sundae_first"],
    "test_band_models.py": ["test_models_run_from_the_cli", "test_readme_band_synthesis_section",
                            "test_balanced_door_needs_no_torque", "test_db_ds_synthesis"],
    "test_user_names.py": ["test_simulate_plots_a_signal_by_its_connector_name"],
    "test_derived_accelerations.py": ["test_seen_3_spring_damper_demo_compares_accelerations"],
    # two seconds of CPU or more each in the fast tier (a command-line process, a
    # compile, a whole-model run); their modules keep faster tests of the same code
    "test_hydraulic_cable_crane.py": ["test_energy_balance_of_the_whole_system_closes"],
    "test_cam_compliant.py": ["test_lift_off_and_re_contact_from_the_cli"],
    "test_user_model_errors.py": ["test_traceback_flag_and_environment_show_the_whole_traceback"],
    "test_fit.py": ["test_pulley_block_friction_recovered_inside_its_interval"],
    "test_cam_follower.py": ["test_cam_model_from_the_cli_writes_figures",
                             "test_knife_edge_on_a_band_synthesised_cam",
                             "test_rigid_lift_off_from_the_cli_exits_2_and_leaves_no_results"],
    "test_slider_ranges.py": ["test_simulate_prints_the_ranges"],
    "test_compare.py": ["test_run_compare_cli"],
    "test_run_hygiene.py": ["test_a_model_without_geometry_gets_no_animation_and_says_so"],
    "test_trust_compare.py": ["test_seen_3_a_reference_signal_without_counterpart_fails_and_is_named"],
}
"""Single tests of otherwise fast modules that start processes (the command
line, a benchmark's small mode, a killed run, a dask cluster) or a browser,
or take more than 4 s of CPU time: {module: [test function names]}."""


FAST_CASES = {
    "test_band_systematics.py": {"test_structure_static_and_power_balance": 4,
                                 "test_two_band_coupler_static_and_power_balance": 2},
    "test_trust_mec2.py": {"test_seen_9_every_example_loads_checks_and_simulates": 5},
    "test_talk_mechanisms.py": {"test_counts_and_closed_loops_over_the_run": 4},
}
"""Parametrized tests over many models of which the fast tier takes the
first few cases (the others are slow): {module: {test function: cases}}."""


def pytest_configure(config):
    """Import the figures' matplotlib modules once per test process: the
    command line draws its figures in a forked child (acausal2d.visual.
    figure_process), which then finds them imported instead of importing
    them anew (1.1-1.25 s of CPU on the 2-core CI machine) for each
    ``simulate`` a test runs in-process.  What the child draws is the same.
    Measured on four modules of such tests (151 tests, -n 2): 92.7 -> 81.4 s
    of CPU.  Tests of what a process imports start their own interpreter.
    Under ``-n`` the controller runs no test: it does not import them."""
    if getattr(config.option, "numprocesses", None) and not hasattr(config, "workerinput"):
        return
    import matplotlib.figure  # noqa: F401
    import matplotlib.backends.backend_agg  # noqa: F401


FIRST = ["test_readme_commands.py", "test_site_build.py", "test_bench_small_modes.py",
         "test_help_examples.py", "test_plain_clone.py", "test_fit_cli.py", "test_ci_run.py",
         "test_talk_mechanisms.py", "test_output_rows.py", "test_fit.py"]
"""Modules that hold the suite's longest tests (a minute or more each on two
cores: the plain clone running every documented command, the documentation
site's build, the benchmarks' small modes).  Under ``-n auto`` they are
started first, dealt in turn to
the workers (:func:`first_for_each_worker`): started last, one of them
alone would make the run's tail.  Whole modules move, so that their
module-scoped fixtures are made once."""


def first_for_each_worker(items, workers):
    """``items`` reordered so that xdist's load scheduling hands worker k
    the modules FIRST[k::workers] at the front of its first chunk.  The
    chunk is xdist's (pytest-xdist 3, LoadScheduling.schedule): a quarter of
    the items per worker.  A run without workers keeps the order."""
    if workers < 2:
        return items
    module = lambda item: os.path.basename(str(item.fspath))     # noqa: E731
    rest = [item for item in items if module(item) not in FIRST]
    chunk = max(2, len(items) // workers // 4)
    out = []
    for k in range(workers):
        heads = [item for m in FIRST[k::workers] for item in items if module(item) == m]
        take = max(0, chunk - len(heads)) if k < workers - 1 else 0
        out += heads + rest[:take]
        rest = rest[take:]
    return out + rest


def pytest_collection_modifyitems(config, items):
    """Mark the tests of :data:`SLOW_MODULES` and :data:`SLOW_TESTS` slow,
    and the cases of :data:`FAST_CASES` beyond the first few; the modules
    of :data:`FIRST` first on each worker."""
    workers = int(getattr(config, "workerinput", {}).get("workercount", 1))
    items[:] = first_for_each_worker(items, workers)
    slow = pytest.mark.slow
    seen = {}
    for item in items:
        module = os.path.basename(str(item.fspath))
        name = getattr(item, "originalname", item.name)
        keep = FAST_CASES.get(module, {}).get(name)
        if keep is not None:
            seen[(module, name)] = seen.get((module, name), 0) + 1
        if module in SLOW_MODULES or name in SLOW_TESTS.get(module, ()) or \
                (keep is not None and seen[(module, name)] > keep):
            item.add_marker(slow)


FUZZ_ALL = os.environ.get("ACAUSAL2D_FUZZ", "") == "all"
FUZZ_SHARE = 0.25
FUZZ_SEED = 46


def fuzz_sample(cases, key="category"):
    """The fuzz cases a run takes, as pytest params: of each class (the
    cases' ``key``) a quarter drawn with a fixed seed (the same cases on
    every run and machine; at least one), all of them with
    ``ACAUSAL2D_FUZZ=all``.  The first case of each class runs in the fast
    tier, the others are marked slow."""
    import random
    groups = {}
    for case in cases:
        groups.setdefault(case[key], []).append(case)
    rng = random.Random(FUZZ_SEED)
    params = []
    for group in groups.values():
        n = len(group) if FUZZ_ALL else max(1, round(FUZZ_SHARE * len(group)))
        picked = sorted(rng.sample(range(len(group)), n))
        for k, i in enumerate(picked):
            params.append(pytest.param(group[i], id=group[i]["id"],
                                       marks=() if k == 0 else pytest.mark.slow))
    return params
