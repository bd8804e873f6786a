namespace ringcrush::fe {}
