rule plot_pair:
    """The tooth profile with its fillet, L(phi), and the contact lines, drawn from the netCDF files."""
    input:
        geometry="results/{study}/{pair}/geometry.nc",
        contact_lines="results/{study}/{pair}/contact_lines.nc",
    output:
        tooth_profile="results/{study}/{pair}/plots/tooth_profile.png",
        contact_length="results/{study}/{pair}/plots/contact_length.png",
        contact_lines="results/{study}/{pair}/plots/contact_lines.png",
    log:
        "logs/{study}/{pair}/plots.log",
    params:
        function="gearmesh.plots.geometry:pair_figures",
    conda:
        ENV
    script:
        "../scripts/plot.py"


rule plot_helix_sweep:
    """The contact-line fluctuation V-curve against helix angle."""
    input:
        helix_sweep="results/{study}/helix_sweep.nc",
    output:
        helix_sweep="results/{study}/plots/helix_sweep.png",
    log:
        "logs/{study}/plots_helix_sweep.log",
    params:
        function="gearmesh.plots.geometry:helix_sweep_figures",
    conda:
        ENV
    script:
        "../scripts/plot.py"
