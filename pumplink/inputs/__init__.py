"""Every file pumplink reads, and nothing else: pump specs (:mod:`~pumplink.inputs.pump`), piston
specs (:mod:`~pumplink.inputs.piston`), batch files for both (:mod:`~pumplink.inputs.batch`),
mechanism files (:mod:`~pumplink.inputs.structure`), their JSON Schemas
(:mod:`~pumplink.inputs.schema`), all read and validated the same way
(:mod:`~pumplink.inputs.toml`)."""
