rule plot_pair:
    """The tooth profile with its fillet, L(phi), and the contact lines, drawn from the netCDF files."""
    input:
        geometry="results/{study}/{pair}/geometry.nc",
        contact_lines="results/{study}/{pair}/contact_lines.nc",
    output:
        tooth_profile=report_item("results/{study}/{pair}/plots/tooth_profile.png", "tooth_profile", "Geometry"),
        contact_length=report_item("results/{study}/{pair}/plots/contact_length.png", "contact_length", "Contact lines"),
        contact_lines=report_item("results/{study}/{pair}/plots/contact_lines.png", "contact_lines", "Contact lines"),
    log:
        "logs/{study}/{pair}/plots.log",
    params:
        function=versioned("gearmesh.plots.geometry:pair_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_helix_sweep:
    """The contact-line fluctuation V-curve against helix angle."""
    input:
        helix_sweep="results/{study}/helix_sweep.nc",
    output:
        helix_sweep=report_item("results/{study}/plots/helix_sweep.png", "helix_sweep", "Contact lines", STUDY_TABLES),
    log:
        "logs/{study}/plots_helix_sweep.log",
    params:
        function=versioned("gearmesh.plots.geometry:helix_sweep_figures"),
    conda:
        ENV
    script:
        "../scripts/plot.py"
